"""The LINE TYPES of a MoorDyn file written from a case (diameter and mass per metre from
the weight in water, EA or a tension-strain curve file, and the dynamic columns: kept from
an imported file, else typical values for chain and rope), and each line's default
NumSegs. Shared by the legs-form and network-form writers."""

from __future__ import annotations

import logging
import math

from ..errors import CaseError
from .moordyn_curves import (MAX_POINTS, chord_departure, curve_file_name, curve_text,
                             is_number, sample_cubic, sample_law, sample_table)

log = logging.getLogger(__name__)
#: Departure of MoorDyn's chords from a monotone-cubic law (relative to its last row's
#: tension) above which the export warns.
CHORD_WARNING = 1e-3

STEEL_DENSITY = 7850.0          # [kg/m^3], for a line type without a diameter
CHAIN_COEFFICIENTS = {"cd": "1.333", "ca": "1.0", "cdax": "0.639", "caax": "0.5"}
ROPE_COEFFICIENTS = {"cd": "1.2", "ca": "1.0", "cdax": "0.008", "caax": "0"}
DEFAULT_BA = "-0.8"
SEGMENT_LENGTH = 5.0            # [m] per MoorDyn segment by default
SEGMENTS_RANGE = (10, 100)


def number_text(value: float) -> str:
    """A value to 12 significant digits (the round trip promises 6), shortest form."""
    if value == 0.0:
        return "0"
    return f"{value:.12g}"


_g = number_text          # short, for the dense table rows below


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-12 * max(abs(a), abs(b))


def export_diameter(lt, env) -> float:
    """MoorDyn's Diam (volume-equivalent diameter) for a case line type."""
    if lt.catalog is not None:
        from .. import catalog
        entry = catalog.entries()[lt.catalog]
        mass = entry.mass_per_length(lt.diameter)
        return math.sqrt(4.0 * mass / (math.pi * entry.material_density))
    if lt.diameter is not None:
        return lt.diameter
    if lt.weight_in_water <= 0:
        raise CaseError(f"line_types.{lt.name}.diameter",
                        "a neutral or buoyant line needs a diameter for MoorDyn (its mass "
                        "per metre follows from the weight in water and the displaced "
                        "volume); give diameter > 0 [m]")
    area = lt.weight_in_water / (env.gravity * (STEEL_DENSITY - env.water_density))
    return math.sqrt(4.0 * area / math.pi)


def _is_chain(lt) -> bool:
    if lt.catalog is not None:
        return lt.catalog.startswith(("studless", "studlink"))
    return "chain" in lt.name.lower()


def _line_type_columns(lt, stored: dict | None) -> dict:
    if stored is not None:
        return dict(stored)
    cols = dict(CHAIN_COEFFICIENTS if _is_chain(lt) else ROPE_COEFFICIENTS)
    if lt.drag is not None:
        cols["cd"] = _g(lt.drag.normal)
        cols["cdax"] = _g(lt.drag.tangential / math.pi)
    cols["ba"] = DEFAULT_BA
    cols["ei"] = "0"
    return cols


def _curve(lt, prefix: str, curves: dict) -> tuple:
    """The EA token and the stiffness (for the time step) of a line type with a stretch law:
    a curve file's name, its text put into ``curves``."""
    law = lt.stretch
    title = f"{lt.name}: {law.describe()}"
    if law.model == "table" and law.interpolation == "linear" and law.rows <= MAX_POINTS:
        strain, tension = law.strain, law.tension
    elif law.model == "table" and law.interpolation == "linear":
        strain, tension = sample_table(law)
        title += f", {MAX_POINTS} of its rows (MoorDyn reads at most {MAX_POINTS})"
    elif law.model == "table":
        # MoorDyn joins the rows by chords: the cubic is sampled between them.
        strain, tension = sample_cubic(law)
        departure = chord_departure(law, strain, tension)
        title += (f", its monotone cubic sampled at {len(strain)} rows (chords within "
                  f"{departure:.2g} of the top tension)")
        if departure > CHORD_WARNING:
            log.warning("line type %s: MoorDyn's linear interpolation of the %d rows written "
                        "departs from the monotone-cubic table by %.2g of its top tension "
                        "(MoorDyn reads at most %d rows); give interpolation: linear with "
                        "the rows MoorDyn should use", lt.name, len(strain), departure,
                        MAX_POINTS)
    else:
        strain, tension = sample_law(law, lt.mbl)
    name = curve_file_name(prefix, lt.name)
    curves[name] = curve_text(title, strain, tension)
    stiffest = max((t1 - t0) / (e1 - e0) for e0, e1, t0, t1 in
                   zip(strain, strain[1:], tension, tension[1:]))
    return name, stiffest


def line_type_rows(case, block: dict, version: int, curve_prefix: str = "",
                    curves: dict | None = None):
    env = case.environment
    stored_types = block.get("line_types", {})
    from_moordyn = "legs" in block
    rows, masses, stiffness = [], {}, {}
    curves = {} if curves is None else curves
    for name, lt in case.line_types.items():
        if not lt.elastic:
            raise CaseError(f"line_types.{name}.ea", "an inextensible line cannot be written "
                                                     "for MoorDyn, which needs EA; give ea [N]")
        diameter = export_diameter(lt, env)
        mass = lt.weight_in_water / env.gravity + env.water_density * math.pi * diameter ** 2 / 4
        if mass < 0:
            raise CaseError(f"line_types.{name}.weight_in_water",
                            f"buoyancy {-lt.weight_in_water:.6g} N/m exceeds what a diameter of "
                            f"{diameter:.6g} m displaces: MoorDyn would need a negative mass "
                            "per metre; give the line's real (volume-equivalent) diameter")
        masses[name] = mass
        stored = stored_types.get(name)
        if stored is None and from_moordyn:
            stored = {}
        cols = _line_type_columns(lt, stored if stored else None)
        if lt.stretch is not None:
            # A tension-strain curve file; dynamic-stiffness values a v2 file gave after
            # its name are kept.
            ea, stiffness[name] = _curve(lt, curve_prefix, curves)
            if "ea" in cols and "|" in cols["ea"] and not is_number(cols["ea"].split("|")[0]):
                ea += "|" + cols["ea"].split("|", 1)[1]
        else:
            ea, stiffness[name] = _g(lt.ea), lt.ea
            if "ea" in cols and is_number(cols["ea"].split("|")[0]):
                if _close(float(cols["ea"].split("|")[0]), lt.ea):
                    ea = cols["ea"]
        defaults = dict(CHAIN_COEFFICIENTS if _is_chain(lt) else ROPE_COEFFICIENTS,
                        ba=DEFAULT_BA, ei="0")
        get = lambda key: cols.get(key, defaults.get(key, "0"))  # noqa: E731
        if version == 1:
            ea = ea.split("|")[0]
            row = [name, _g(diameter), _g(mass), ea, get("ba"), get("ca"), get("caax"),
                   get("cd"), get("cdax")]
        else:
            row = [name, _g(diameter), _g(mass), ea, get("ba"), get("ei"), get("cd"),
                   get("ca"), get("cdax"), get("caax")]
            extra = [cols.get(k) for k in ("cl", "df", "cf")]
            if any(v is not None for v in extra):
                row += [v if v is not None else d for v, d in zip(extra, ("0", "0.08", "0.18"))]
        rows.append(row)
    return rows, masses, stiffness


def default_num_segs(length: float) -> int:
    return int(min(max(math.ceil(length / SEGMENT_LENGTH), SEGMENTS_RANGE[0]),
                   SEGMENTS_RANGE[1]))
