"""Imported files solved by moorsolve and by MoorPy (optional: the ``bench`` extra's MoorPy
1.3.0): every MoorDyn line's end tensions agree to 1e-4 (they agree to about 1e-7; MoorPy's
own catenary tolerance is the limit).

MoorPy reads a file itself where its parser can (v2 files without comment lines, count
rows or rod ends; MoorPy's YAML). Its defaults differ from MoorDyn's, so the environment the
import took (MoorDyn's: g 9.80665 where the file gives none, the depth of the deepest point
without WtrDpth) is set on the MoorPy System after loading; and MoorPy reads a Z of
``seabed`` before it has read WtrDpth (the anchor lands at z = 0), so such points are put on
the seabed. The other files are compared through moorsolve's own export: imported, written
as MoorDyn v2, read by MoorPy.
"""

import contextlib
import io
import re
import warnings

import numpy as np
import pytest

import moorsolve
from moorsolve.io import read_import, read_moorpy

mp = pytest.importorskip("moorpy")

from test_moordyn_corpus import DATA, FORMS  # noqa: E402

MOORPY_DATA = DATA.parent / "moorpy"
#: Files MoorPy 1.3.0's own parser reads.
MOORPY_READS = {"semisub_v2.dat", "buoy_single_fairlead_v2.dat", "openfast_v2_seabed.dat"}


def _moorpy(path, env, seabed=(), hold=True):
    """MoorPy's equilibrium of a file: ``{line number: (TA, TB)}``.

    MoorPy makes the vessel of its YAML a free body without mass (it would drift until the
    lines go slack); a held vessel, as moorsolve imports it, is what is compared (``hold``;
    a MoorDyn Free body is left free).
    """
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ms = mp.System(file=str(path))
        ms.g, ms.rho, ms.depth = env.gravity, env.water_density, env.depth
        for number in seabed:
            ms.pointList[number - 1].r[2] = -env.depth
        for body in ms.bodyList:
            if hold:
                body.type = 1 if body.type == 0 else body.type
            # MoorDyn-C puts a body's buoyancy at its CG (MoorPy: at rM, the origin).
            body.rM = np.array(body.rCG, dtype=float)
        ms.initialize()
        assert ms.solveEquilibrium(DOFtype="free", tol=1e-7, maxIter=500, no_fail=True)
        out = {}
        for i, line in enumerate(ms.lineList, start=1):
            line.staticSolve(tol=1e-10)
            out[i] = (line.TA, line.TB)
    return out


def _ours(data, result) -> dict:
    """moorsolve's ``{MoorDyn line number: (TA, TB)}`` (the file's line order)."""
    if "lines" in data:                              # network form: line<N>, end A first
        return {k + 1: (leg.anchor_tension_N, leg.fairlead_tension_N)
                for k, leg in enumerate(result.legs)}
    out = {}
    block = data.get("moordyn", {}).get("legs")
    for k, leg in enumerate(result.legs):
        if block is None:                            # a MoorPy YAML: one line per leg
            out[k + 1] = (leg.anchor_tension_N, leg.fairlead_tension_N)
            continue
        lines = block[leg.name]["lines"]
        segs = leg.segments or ({"bottom_tension_N": leg.anchor_tension_N,
                                 "top_tension_N": leg.fairlead_tension_N},)
        for line, seg in zip(lines, segs):
            ends = (seg["bottom_tension_N"], seg["top_tension_N"])
            out[line["id"]] = ends[::-1] if line["reversed"] else ends
    return out


def _compare(ours, theirs, rel=1e-4, skip=()):
    assert ours.keys() == theirs.keys()
    scale = max(max(t) for t in theirs.values())
    for number, (ta, tb) in theirs.items():
        if number in skip:
            continue
        a, b = ours[number]
        assert a == pytest.approx(ta, rel=rel, abs=1e-6 * scale), (number, "A")
        assert b == pytest.approx(tb, rel=rel, abs=1e-6 * scale), (number, "B")


#: Files where the two models differ, and why (tolerance, or lines left out).
DIFFERENT = {
    # A 20 t sinker resting on the seabed: MoorPy ramps a point's seabed reaction over its
    # zTol, moorsolve's joint rests exactly on it; 4e-4 apart on the sinker's chain.
    "spar_v1.dat": {"rel": 1e-3},
}


@pytest.mark.parametrize("name", sorted(n for n, (f, _) in FORMS.items() if f == "legs"))
def test_legs_files_agree_with_moorpy(name, tmp_path):
    from moorsolve.checks.modelling import modelling_warnings
    imp = read_import(DATA / name)
    case = moorsolve.load_case(imp.data)
    result = moorsolve.solve(case)
    # A line the modelling checks flag as passing below the seabed would be a model
    # difference, not an import error: flagged lines are left out (none are, today).
    flagged = {w.subject for w in modelling_warnings(case, result) if w.code == "below_seabed"}
    if name in MOORPY_READS:
        seabed = [int(r.values[0]) for r in imp.file.tables["points"]
                  if r.values[4].lower() == "seabed"]
        theirs = _moorpy(DATA / name, case.environment, seabed)
    else:
        path = tmp_path / "exported.dat"
        moorsolve.export_moordyn(case, path, version=2)
        # MoorPy refuses MoorDyn's two-part body CdA ("15|60") and does not know the Point
        # keyword of a free point (it keeps the type of the row before); MoorDyn reads both.
        text = path.read_text().replace("15|60", "15")
        path.write_text(re.sub(r"^(\d+\s+)Point(\s)", r"\1Free\2", text, flags=re.M))
        exported = read_import(path)
        theirs = _moorpy(path, case.environment)
        result = moorsolve.solve(moorsolve.load_case(exported.data))
        imp = exported
    legs = imp.data["moordyn"]["legs"]
    skip = {line["id"] for leg in flagged for line in legs[leg]["lines"]}
    _compare(_ours(imp.data, result), theirs, skip=skip, **DIFFERENT.get(name, {}))


def test_moorpy_yaml_agrees_with_moorpy():
    path = MOORPY_DATA / "spread_moorpy.yaml"
    data = read_moorpy(path).data
    case = moorsolve.load_case(data)
    result = moorsolve.solve(case)
    assert case.environment.gravity == 9.81                  # MoorPy's default
    _compare(_ours(data, result), _moorpy(path, case.environment))


def test_exported_moorpy_yaml_is_what_moorpy_reads(tmp_path):
    case = moorsolve.load_case(read_import(DATA / "semisub_v2.dat").data)
    out = tmp_path / "semi.yaml"
    moorsolve.export_moorpy(case, out)
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ms = mp.System(file=str(out))
        ms.g = case.environment.gravity
        ms.bodyList[0].type = 1                     # held, as the case's body is
        ms.initialize()
        ms.solveEquilibrium(DOFtype="free", tol=1e-7, maxIter=500, no_fail=True)
        for line in ms.lineList:
            line.staticSolve(tol=1e-10)
    result = moorsolve.solve(case)
    # The first line of each leg starts at its anchor; the last ends at its fairlead.
    k = 0
    for leg in result.legs:
        n = len(leg.segments) or 1
        assert ms.lineList[k].TA == pytest.approx(leg.anchor_tension_N, rel=1e-4)
        assert ms.lineList[k + n - 1].TB == pytest.approx(leg.fairlead_tension_N, rel=1e-4)
        k += n
    assert k == len(ms.lineList)
    assert np.isclose(ms.depth, case.environment.depth)


#: Network files MoorPy 1.3.0 reads and solves the same way: bridle, hub, dangling buoys,
#: two held bodies with a shared line, a free six-DOF body, a chain between two fixed points
#: under stale column names (MoorPy, unlike MoorDyn, holds a CoupledPinned body and knows
#: no FAST.Farm turbine, rod, g = 0 or tilted body frame).
MOORPY_NETWORK = ["bridle_v2.dat", "hub_v2.dat", "dangling_buoys_v2.dat",
                  "shared_line_two_bodies_v2.dat", "free_buoy_six_dof_v2.dat",
                  "stale_names_v2.dat"]


@pytest.mark.parametrize("name", MOORPY_NETWORK)
def test_network_files_agree_with_moorpy(name):
    imp = read_import(DATA / name)
    case = moorsolve.load_case(imp.data)
    result = moorsolve.solve(case)
    _compare(_ours(imp.data, result), _moorpy(DATA / name, case.environment, hold=False))


def test_moorpy_yaml_bridle_agrees_with_moorpy():
    path = MOORPY_DATA / "bridle_buoy_moorpy.yaml"
    data = read_moorpy(path).data
    case = moorsolve.load_case(data)
    _compare(_ours(data, moorsolve.solve(case)), _moorpy(path, case.environment))
