"""The declaration machinery of the case-file schema: :class:`Key`, :class:`Section` and
the registry every section joins (see :mod:`moorsolve.model.schema`)."""


from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType

from ..units import KINDS

__all__ = ["Key", "Section", "REQUIRED", "NONE", "TYPES", "SECTIONS", "section", "get", "default"]


class _Marker:
    def __init__(self, text: str):
        self.text = text

    def __repr__(self) -> str:
        return self.text


#: The key must be given.
REQUIRED = _Marker("required")
#: Absent (or null) means "none": the feature is off.
NONE = _Marker("none")

#: Value types of keys that are not quantities (quantities use a kind of
#: :data:`moorsolve.model.units.KINDS`).
TYPES = {
    "text": "text",
    "bool": "true or false",
    "integer": "integer",
    "choice": "one of",
    "mapping": "mapping",
    "list": "list",
    "end": "line end",
    "weight": "N/m or a mass per length (kg/m, t/m)",
    "file": "file name or mapping",
    "any": "free-form",
}


@dataclass(frozen=True)
class Key:
    """One key of a section.

    Parameters
    ----------
    doc : str
        One line: what the key means.
    kind : str
        A quantity kind of :data:`~moorsolve.model.units.KINDS` (its SI unit is the key's
        unit; a value may carry any unit of that kind) or a type of :data:`TYPES`.
    default : object
        :data:`REQUIRED`, :data:`NONE` (absent means none) or the value taken when absent
        (SI; a tuple for a list).
    range : str
        The allowed values, e.g. ``"> 0, <= 12 km"``.
    choices : tuple
        The allowed values of a ``choice`` (or the allowed items of a ``list``).
    shape : str
        The form of a list value, e.g. ``"[x, y, z]"``.
    section : str
        The section (or sections, ``|``-separated by variant) that describes a mapping value.
    also : tuple
        Other quantity kinds the items of a list or row take (``[Fx, Fy, Mz]``: a force
        with ``also=("moment",)``).
    """

    doc: str
    kind: str = "any"
    default: object = NONE
    range: str = ""
    choices: tuple = ()
    shape: str = ""
    section: str = ""
    also: tuple = ()

    def __post_init__(self):
        for kind in (self.kind,) + tuple(self.also):
            if kind not in KINDS and kind not in TYPES:
                raise ValueError(f"unknown kind {kind!r}")

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    @property
    def kinds(self) -> tuple:
        """Every quantity kind the value's numbers take."""
        return tuple(k for k in (self.kind,) + tuple(self.also) if k in KINDS)

    @property
    def unit(self) -> str:
        """The SI units of its quantities, e.g. ``"N, N m"`` ("" for a plain number or a
        non-quantity)."""
        return ", ".join(u for u in dict.fromkeys(KINDS[k][1] for k in self.kinds) if u)


@dataclass(frozen=True)
class Section:
    """A mapping of a case file: where it sits, what it is, and its keys."""

    name: str
    where: str
    doc: str
    keys: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))

    @property
    def required(self) -> tuple:
        return tuple(k for k, v in self.keys.items() if v.required)

    @property
    def optional(self) -> tuple:
        return tuple(k for k, v in self.keys.items() if not v.required)


#: Every section by name, in declaration order (the reference page's order).
SECTIONS: dict = {}


def section(name: str, where: str, doc: str, keys: dict) -> Section:
    """Declare (register) a section; a name may be declared once."""
    if name in SECTIONS:
        raise ValueError(f"section {name!r} is declared twice")
    made = Section(name=name, where=where, doc=doc, keys=MappingProxyType(dict(keys)))
    SECTIONS[name] = made
    return made


def get(name: str) -> Section:
    """The section ``name`` (a KeyError names the known ones)."""
    try:
        return SECTIONS[name]
    except KeyError:
        raise KeyError(f"no case-file section {name!r}; known: {', '.join(SECTIONS)}") from None


def default(name: str, key: str):
    """The default value of ``key`` in section ``name`` (SI)."""
    value = get(name).keys[key].default
    if value is REQUIRED or value is NONE:
        raise ValueError(f"{name}.{key} has no default value ({value!r})")
    return value

