"""The Python entry points the README promises: ``moorsolve.solve`` of a dict and
``Result.to_frame()``."""

from __future__ import annotations

import math

import numpy as np
import pytest
import yaml
from conftest import ROOT

import moorsolve
from moorsolve.errors import CaseError


def _data(name):
    return yaml.safe_load((ROOT / "cases" / name).read_text(encoding="utf-8"))


def test_a_dict_is_solved_as_load_case_would_load_it():
    data = _data("buoy_vida.yaml")
    from_dict = moorsolve.solve(data)
    from_case = moorsolve.solve(moorsolve.load_case(data))
    assert from_dict.body == pytest.approx(from_case.body, abs=1e-9)
    for a, b in zip(from_dict.legs, from_case.legs):
        assert a.fairlead_tension_N == pytest.approx(b.fairlead_tension_N, rel=1e-9)


def test_a_bad_dict_is_a_case_error_naming_the_field():
    data = _data("buoy_vida.yaml")
    data["legs"][0]["segments"][0]["length"] = -5
    with pytest.raises(CaseError, match=r"legs\[0\]\.segments\[0\]\.length"):
        moorsolve.solve(data)


@pytest.mark.parametrize("name", ["floating_dock_sloped.yaml", "chain_polyester_clump.yaml"])
def test_the_frame_holds_every_scalar_and_vector_field_of_every_line(name):
    result = moorsolve.solve(moorsolve.load_case(ROOT / "cases" / name))
    frame = result.to_frame()
    assert list(frame.index) == [leg.name for leg in result.legs]
    for leg in result.legs:
        row = frame.loc[leg.name]
        for key, value in leg.to_dict(profile=False).items():
            if key in ("name", "segments", "joints"):
                continue
            if isinstance(value, list):
                stem, unit = key.rsplit("_", 1)
                got = [row[f"{stem}_{axis}_{unit}"] for axis in "xyz"]
                np.testing.assert_allclose(got, value, rtol=0, atol=0)
            elif value is None:
                cols = [c for c in frame.columns if c == key or c.startswith(key[:-2] + "_")]
                assert all(row[c] is None or (isinstance(row[c], float) and math.isnan(row[c]))
                           for c in cols), key
            else:
                assert row[key] == value, key


def test_a_line_without_a_touchdown_has_nan_components_beside_one_with_it():
    result = moorsolve.solve(moorsolve.load_case(ROOT / "cases" / "floating_dock.yaml"))
    frame = result.to_frame()
    lifted = [leg.name for leg in result.legs if leg.touchdown_point is None]
    grounded = [leg.name for leg in result.legs if leg.touchdown_point is not None]
    assert lifted and grounded
    assert frame.loc[lifted, "touchdown_point_x_m"].isna().all()
    assert frame.loc[grounded, "touchdown_point_x_m"].notna().all()
    assert "touchdown_point_m" not in frame.columns
