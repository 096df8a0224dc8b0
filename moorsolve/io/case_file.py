"""Read a case file (YAML) or case dictionary into a validated :class:`~moorsolve.model.Case`.

YAML is read strictly (duplicate keys are errors); the data is validated by
:func:`moorsolve.model.build_case`.
"""

from __future__ import annotations

from collections.abc import Mapping
from os import PathLike
from pathlib import Path

import yaml

from ..errors import CaseError
from ..model import Case
from ..model.edit import build_with_source
from .bathymetry import resolve_in_case
from .wamit import resolve_in_case as resolve_wamit
from ..model.fields import FAIRLEAD_Z_MAX
from ..model.units import show_value

__all__ = ["load_case", "FAIRLEAD_Z_MAX"]


class _StrictLoader(yaml.SafeLoader):
    """A safe YAML loader that rejects duplicate mapping keys instead of keeping the last."""


def _construct_strict_mapping(loader, node):
    seen = set()
    for key_node, _ in node.value:
        if key_node.tag == "tag:yaml.org,2002:merge":
            continue
        key = loader.construct_object(key_node, deep=True)
        try:
            duplicate = key in seen
        except TypeError:
            raise yaml.constructor.ConstructorError(
                "while constructing a mapping", node.start_mark, "found an unhashable key",
                key_node.start_mark) from None
        if duplicate:
            raise yaml.constructor.ConstructorError(
                "while constructing a mapping", node.start_mark,
                f"found duplicate key {key!r}", key_node.start_mark)
        seen.add(key)
    return loader.construct_mapping(node, deep=True)


_StrictLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG,
                              _construct_strict_mapping)


def _yaml_message(exc: Exception) -> str:
    mark = getattr(exc, "problem_mark", None)
    problem = getattr(exc, "problem", None)
    if mark is not None and problem:
        return f"invalid YAML at line {mark.line + 1}, column {mark.column + 1}: {problem}"
    return "invalid YAML: " + " ".join(str(exc).split())


def _read_yaml(path: Path):
    label = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise CaseError(label, "case file not found") from None
    except IsADirectoryError:
        raise CaseError(label, "is a directory, not a case file") from None
    except UnicodeDecodeError as exc:
        raise CaseError(label, f"is not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    except (OSError, ValueError) as exc:
        raise CaseError(label, f"cannot read the case file: {exc}") from None
    try:
        data = yaml.load(text, Loader=_StrictLoader)
    except RecursionError:
        raise CaseError(label, "invalid YAML: nested too deeply") from None
    except Exception as exc:  # YAMLError, and ValueError from e.g. a date like 2020-13-45
        raise CaseError(label, _yaml_message(exc)) from None
    if not isinstance(data, Mapping):
        raise CaseError(label, f"the file holds {type(data).__name__}, not a mapping; a case "
                               "file has the keys environment, line_types, legs (and optionally "
                               "name, body, solver)")
    return data


def load_case(source, *, keep_source: bool = True) -> Case:
    """Load and validate a mooring case.

    Parameters
    ----------
    source : str, pathlib.Path or mapping
        Path to a YAML case file, or a dictionary of the same shape.
    keep_source : bool
        Keep a copy of the case-file data as ``Case.source`` (what sweeps edit) and warn
        about inputs that no model uses; a caller that validates many throw-away variants
        of a case already loaded may skip both.

    Returns
    -------
    moorsolve.model.Case
        The validated case, in SI units. Its name defaults to the file stem (or ``"case"``
        for a dictionary).

    Warns
    -----
    UnusedInputWarning
        For each input that no model uses (:func:`moorsolve.model.usage.unused_inputs`):
        waves without a wave-drift model, a current neither the body nor a line feels, ...

    Raises
    ------
    CaseError
        For any problem with the input; ``field`` is the dotted path of the offending value
        (``legs[3].segments[0].length``), or the file name for a file that cannot be read or
        parsed. No other exception escapes.

    Notes
    -----
    Checks beyond the schema: anchors lie on or above the seabed and below their fairlead;
    fairleads lie above the seabed and at most :data:`FAIRLEAD_Z_MAX` above still water; an
    inextensible line is at least as long as the straight distance from its anchor to its
    fairlead at the case-file position (body at zero offset); leg names are unique; clump
    items sit between two segments.

    Examples
    --------
    >>> case = load_case("cases/floating_dock.yaml")  # doctest: +SKIP
    >>> case.legs[0].anchor  # doctest: +SKIP
    (-240.0, -120.0, -20.85)
    """
    if isinstance(source, (str, PathLike)):
        try:
            path = Path(source)
        except TypeError:
            raise CaseError("", f"{show_value(source)} is not a usable path") from None
        data = _read_yaml(path)
        default_name = path.stem or "case"
        base = path.parent
    elif isinstance(source, Mapping):
        data, default_name, base = source, "case", Path.cwd()
    else:
        raise CaseError("", f"{show_value(source)} is not a case: give a path to a YAML file or a "
                            "dict")
    # A bathymetry file is read here (io), relative to the case file; the source keeps
    # its absolute name, so a sweep's edited copy reads it from anywhere.
    built, data = resolve_in_case(data, base)
    # WAMIT files likewise: read here, their names kept absolute in the source.
    built, kept = resolve_wamit(built, base)
    if kept is not built:
        data = resolve_wamit(data, base)[1]
    return build_with_source(built, data, default_name, keep_source, stacklevel=3)
