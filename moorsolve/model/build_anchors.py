"""Validate ``checks.anchors``: one anchor design per anchor kind.

Schema (SI units or strings with units)::

    checks:
      anchors:
        drag:       {capacity: > 0 [N]}                      the ultimate holding capacity
                  | {fluke_weight: > 0 [mass], soil: SOIL,   the maker's curve
                     design: stevpris_mk6}                   (moorsolve.catalog.anchors)
                    + optional mass [kg] (for the cost; default the fluke weight)
        suction:    {h_max, v_max: > 0 [N], length, diameter: > 0 [m], mass}
        pile:       {h_max, v_max: > 0 [N], mass}
        deadweight: {mass}                                   (the cost only)
        each optionally embedment: EMBEDMENT
    SOIL: soft_clay | medium_clay | hard_clay | sand
    EMBEDMENT: {padeye_depth: > 0 [m], su0: >= 0 [Pa], su_gradient: >= 0 [Pa/m],
                line_diameter: > 0 [m] (default: a catalogue line type's diameter),
                bearing_factor: > 0 (N_c, default 8.5), bearing_width: > 0 (A_b, 2.5),
                friction: >= 0 (mu, 0.4)}
"""

from __future__ import annotations

from ..catalog import anchors as anchor_catalog
from ..errors import CaseError
from .anchors import SOILS, AnchorDesign, Embedment
from .fields import check_mapping, field_path, nullable_quantity, optional_quantity, quantity
from .units import show_value

__all__ = ["build_anchors", "ANCHOR_DESIGN_KINDS"]

#: Anchor kinds ``checks.anchors`` may describe.
ANCHOR_DESIGN_KINDS = ("drag", "suction", "pile", "deadweight")
_EMBED = "embedment"


def build_anchors(raw, path: str) -> tuple:
    """``checks.anchors`` -> a tuple of AnchorDesign, one per kind given."""
    m = check_mapping(raw, path, section="anchor_designs")
    return tuple(_BUILDERS[kind](entry, field_path(path, kind))
                 for kind, entry in m.items() if entry is not None)


def _mass(m: dict, path: str):
    return nullable_quantity(m, path, "mass", "mass", gt=0)


def _drag(raw, path: str) -> AnchorDesign:
    m = check_mapping(raw, path, section="anchor_design_drag")
    embed = _embedment(m, path)
    if m.get("capacity") is not None:
        for key in ("fluke_weight", "soil", "design"):
            if m.get(key) is not None:
                raise CaseError(field_path(path, key),
                                "give either capacity or fluke_weight with soil, not both")
        capacity = quantity(m["capacity"], field_path(path, "capacity"), "force", gt=0)
        return AnchorDesign(kind="drag", capacity=capacity, mass=_mass(m, path),
                            embedment=embed)
    if m.get("fluke_weight") is None:
        raise CaseError(path, "a drag anchor needs capacity [N] or fluke_weight [mass] "
                              "with soil")
    weight = quantity(m["fluke_weight"], field_path(path, "fluke_weight"), "mass", gt=0)
    soil = m.get("soil")
    if soil is None or soil not in SOILS:
        raise CaseError(field_path(path, "soil"),
                        f"{show_value(soil)} is not a soil with a holding-capacity curve; "
                        f"allowed: {', '.join(SOILS)}")
    design = m.get("design", anchor_catalog.DEFAULT_DESIGN)
    designs = sorted({d for d, _ in anchor_catalog.drag_curves()})
    if design not in designs:
        raise CaseError(field_path(path, "design"),
                        f"unknown anchor design {show_value(design)}; allowed: "
                        f"{', '.join(designs)}")
    curve = anchor_catalog.drag_curve(soil, design)
    mass = _mass(m, path)
    return AnchorDesign(kind="drag", capacity=curve.capacity_N(weight), soil=soil,
                        design=design, mass=weight if mass is None else mass,
                        embedment=embed,
                        capacity_source=f"{design} in {soil.replace('_', ' ')}, "
                                        f"{weight / 1e3:g} t: {curve.source}")


def _hv(m: dict, path: str) -> tuple:
    return (quantity(m["h_max"], field_path(path, "h_max"), "force", gt=0),
            quantity(m["v_max"], field_path(path, "v_max"), "force", gt=0))


def _suction(raw, path: str) -> AnchorDesign:
    m = check_mapping(raw, path, section="anchor_design_suction")
    h, v = _hv(m, path)
    length = quantity(m["length"], field_path(path, "length"), "length", gt=0)
    diameter = quantity(m["diameter"], field_path(path, "diameter"), "length", gt=0)
    embed = _embedment(m, path)
    if embed is not None and embed.padeye_depth >= length:
        raise CaseError(field_path(field_path(path, _EMBED), "padeye_depth"),
                        f"{embed.padeye_depth:g} m must be above the skirt tip "
                        f"(length {length:g} m)")
    return AnchorDesign(kind="suction", h_max=h, v_max=v, length=length, diameter=diameter,
                        mass=_mass(m, path), embedment=embed)


def _pile(raw, path: str) -> AnchorDesign:
    m = check_mapping(raw, path, section="anchor_design_pile")
    h, v = _hv(m, path)
    return AnchorDesign(kind="pile", h_max=h, v_max=v, mass=_mass(m, path),
                        embedment=_embedment(m, path))


def _deadweight(raw, path: str) -> AnchorDesign:
    m = check_mapping(raw, path, section="anchor_design_deadweight")
    return AnchorDesign(kind="deadweight", mass=_mass(m, path))


def _embedment(m: dict, path: str):
    if m.get(_EMBED) is None:
        return None
    epath = field_path(path, _EMBED)
    e = check_mapping(m[_EMBED], epath, section="embedment")
    depth = quantity(e["padeye_depth"], field_path(epath, "padeye_depth"), "length", gt=0)
    su0 = quantity(e["su0"], field_path(epath, "su0"), "pressure", ge=0)
    k = quantity(e["su_gradient"], field_path(epath, "su_gradient"), "pressure_per_length",
                 ge=0)
    if su0 == 0 and k == 0:
        raise CaseError(field_path(epath, "su0"), "the soil has no strength (su0 and "
                                                  "su_gradient both 0): give either > 0")
    defaults = Embedment(padeye_depth=depth, su0=su0, su_gradient=k)
    return Embedment(
        padeye_depth=depth, su0=su0, su_gradient=k,
        line_diameter=nullable_quantity(e, epath, "line_diameter", "length", gt=0, le=1.0),
        bearing_factor=optional_quantity(e, epath, "bearing_factor", "dimensionless",
                                         defaults.bearing_factor, gt=0),
        bearing_width=optional_quantity(e, epath, "bearing_width", "dimensionless",
                                        defaults.bearing_width, gt=0),
        friction=optional_quantity(e, epath, "friction", "dimensionless", defaults.friction,
                                   ge=0, le=2))


_BUILDERS = {"drag": _drag, "suction": _suction, "pile": _pile, "deadweight": _deadweight}
