"""The line catalogue against its published sources (moorsolve/catalog/lines.csv)."""

import pytest

import moorsolve
from moorsolve.catalog import entries, line_properties
from moorsolve.errors import CaseError


def test_hu_tang_am2_48mm_breaking_load():
    # Hu & Tang 2004 (seed 001) section 3: AM2 (grade U2) 48 mm chain, breaking load 1270 kN
    # (printed to 4 digits), safety factor 1270 / 130.9 = 9.7.
    chain = line_properties("studlink_u2", 0.048)
    assert chain.mbl / 1e3 == pytest.approx(1270, abs=0.5)
    assert chain.mbl / 130.9e3 == pytest.approx(9.7, abs=0.05)


@pytest.mark.parametrize("name, c", [("r3", 0.0223), ("r3s", 0.0249), ("r4", 0.0274),
                                     ("r4s", 0.0304), ("r5", 0.0320)])
def test_offshore_grade_mbl_formula(name, c):
    # DNV-OS-E302: MBL = c d^2 (44 - 0.08 d) kN, d in mm; studless and studlink alike.
    for kind in ("studless", "studlink"):
        p = line_properties(f"{kind}_{name}", 0.076)
        assert p.mbl == pytest.approx(c * 76**2 * (44 - 0.08 * 76) * 1e3, rel=1e-12)
    # 76 mm R3: 4884 kN.
    assert line_properties("studless_r3", 0.076).mbl / 1e3 == pytest.approx(4884, abs=0.5)


def test_chain_mass_stiffness_and_submerged_weight():
    d = 0.081
    studless = line_properties("studless_r3", d, water_density=1025, gravity=9.80665)
    studlink = line_properties("studlink_u3", d)
    assert studless.mass_per_length == pytest.approx(0.0199 * 81**2)       # 130.6 kg/m
    assert studlink.mass_per_length == pytest.approx(0.0219 * 81**2)
    assert studless.ea == pytest.approx(0.854e11 * d**2)                   # 5.60e8 N
    assert studlink.ea == pytest.approx(1.01e11 * d**2)
    assert studless.weight_in_water == pytest.approx(
        studless.mass_per_length * 9.80665 * (1 - 1025 / 7850))
    # The ship grade U3 is weaker than offshore R3 at the same size.
    assert studlink.mbl < studless.mbl
    assert studlink.mbl / 1e3 == pytest.approx(0.01961 * 81**2 * (44 - 0.08 * 81), rel=1e-12)


def test_ropes_and_buoyancy():
    poly = line_properties("polyester", 0.1)
    assert poly.mbl == pytest.approx(170466 * 0.1**2 * 1e3)
    assert poly.ea == pytest.approx(1.09e6 * 0.1**2 * 1e3)
    assert line_properties("polypropylene", 0.1).weight_in_water < 0     # floats
    assert line_properties("wire_iwrc", 0.05).weight_in_water > 0
    assert all(e.mbl_source and e.mass_ea_source for e in entries().values())


def test_corrosion_allowance_reduces_only_the_mbl():
    nominal = line_properties("studless_r4", 0.1)
    corroded = line_properties("studless_r4", 0.1, corrosion_allowance=0.004)
    assert corroded.mbl == pytest.approx(line_properties("studless_r4", 0.096).mbl)
    assert (corroded.ea, corroded.weight_in_water) == (nominal.ea, nominal.weight_in_water)


def _case(line):
    return {"environment": {"depth": 20, "water_density": 1000, "gravity": 10},
            "line_types": {"c": line},
            "legs": [{"name": "A", "anchor": [0, 0], "fairlead": [80, 0, 0],
                      "segments": [{"type": "c", "length": 100}]}]}


def test_case_file_catalogue_line_and_overrides():
    lt = moorsolve.load_case(_case({"catalog": "studless_r3", "diameter": "81 mm",
                                    "corrosion_allowance": "3 mm"})).line_types["c"]
    ref = line_properties("studless_r3", 0.081, water_density=1000, gravity=10,
                          corrosion_allowance=0.003)
    assert (lt.weight_in_water, lt.ea, lt.mbl) == pytest.approx(
        (ref.weight_in_water, ref.ea, ref.mbl))
    assert lt.catalog == "studless_r3" and "DNV-OS-E302" in lt.source
    lt = moorsolve.load_case(_case({"catalog": "studless_r3", "diameter": "81 mm",
                                    "weight_in_water": "0.13 t/m", "mbl": "5 MN"})
                             ).line_types["c"]
    assert lt.weight_in_water == pytest.approx(1300) and lt.mbl == 5e6


@pytest.mark.parametrize("line, field", [
    ({"catalog": "studless_x9", "diameter": 0.08}, "line_types.c.catalog"),
    ({"catalog": "studless_r3"}, "line_types.c.diameter"),
    ({"catalog": "studless_r3", "diameter": "-8 mm"}, "line_types.c.diameter"),
    ({"catalog": "studless_r3", "diameter": "80 mm", "corrosion_allowance": "80 mm"},
     "line_types.c.corrosion_allowance"),
    ({"catalog": "studless_r3", "diameter": "80 mm", "grade": "R3"}, "line_types.c.grade"),
    ({"catalog": "studless_r3", "diameter": "80 mm", "mbl": "5 MN",
      "corrosion_allowance": "2 mm"}, "line_types.c.corrosion_allowance"),
])
def test_catalogue_line_validation(line, field):
    with pytest.raises(CaseError) as err:
        moorsolve.load_case(_case(line))
    assert err.value.field == field
