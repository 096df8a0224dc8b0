"""Edits of a loaded case made on the model (``Case.with_values``, ``moorsolve.model.edit``):
what sweeps, load tables and design studies use instead of reading case files again."""

from __future__ import annotations

import shutil
import warnings

import pytest

import moorsolve
from moorsolve.errors import CaseError, UnusedInputWarning
from moorsolve.model.edit import from_source, inline_source, variant

from conftest import ROOT

DOCK = ROOT / "cases" / "floating_dock.yaml"
BATHY = ROOT / "cases" / "dock_bathymetry.yaml"


def test_with_values_is_load_case_of_the_edited_data():
    """The same case as load_case of the edited case-file data: values, units, source."""
    case = moorsolve.load_case(DOCK)
    edits = {"environment.wind.speed": "30 kn", "legs[L3].segments[0].length": 250.0}
    edited = case.with_values(edits)
    expected = moorsolve.load_case(moorsolve.model.paths.with_values(case.source, edits))
    assert edited == expected
    assert edited.environment.wind.speed == pytest.approx(30 * 1852 / 3600, rel=1e-15)
    assert edited.source == expected.source and edited.name == case.name
    assert case.environment.wind.speed != edited.environment.wind.speed   # case untouched
    bare = case.with_values(edits, keep_source=False)
    assert bare == edited and bare.source is None


def test_with_values_names_the_field_of_a_bad_value():
    case = moorsolve.load_case(DOCK)
    with pytest.raises(CaseError) as err:
        case.with_values({"legs[L3].segments[0].length": -5.0})
    assert err.value.field == "legs[2].segments[0].length"
    with pytest.raises(CaseError) as err:
        variant(case, {"legs[L3].segments[0].length": -5.0}, "load_cases[2].set")
    assert err.value.field == "load_cases[2].set: legs[2].segments[0].length"
    assert variant(case, {}) is case


def test_with_values_warns_of_unused_inputs_as_load_case_does():
    case = moorsolve.load_case(DOCK)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        case.with_values({"environment.waves.hs": 3.0})
        loaded = len([w for w in seen if issubclass(w.category, UnusedInputWarning)])
        seen.clear()
        moorsolve.load_case(moorsolve.model.paths.with_values(case.source,
                                                              {"environment.waves.hs": 3.0}))
        assert loaded == len([w for w in seen if issubclass(w.category, UnusedInputWarning)])


def test_a_case_built_in_code_has_no_data_to_edit():
    case = moorsolve.load_case(DOCK, keep_source=False)
    with pytest.raises(CaseError, match="case-file data"):
        case.with_values({"environment.wind.speed": 10.0})


def test_an_edit_reads_no_bathymetry_file(tmp_path):
    """The grid a case read from its file is the grid its edits hold: the file may be gone
    (a worker without it); naming another file is refused, naming the field."""
    for name in ("dock_bathymetry.yaml", "dock_bathymetry_seafloor.txt"):
        shutil.copy(ROOT / "cases" / name, tmp_path / name)
    case = moorsolve.load_case(tmp_path / "dock_bathymetry.yaml")
    (tmp_path / "dock_bathymetry_seafloor.txt").unlink()
    edited = case.with_values({"environment.wind.speed": 20.0})
    assert edited.environment.seabed.bathymetry == case.environment.seabed.bathymetry
    assert edited.environment.seabed.bathymetry.source == \
        case.environment.seabed.bathymetry.source
    assert edited.lines == case.lines and edited.environment.wind.speed == 20.0
    with pytest.raises(CaseError) as err:
        case.with_values({"environment.seabed.bathymetry": str(tmp_path / "other.txt")})
    assert err.value.field == "environment.seabed.bathymetry"
    # Plain data that travels to a worker: the grid inline, rebuilt without a file.
    again = from_source(inline_source(case))
    assert again == case and again.name == case.name


def test_from_source_of_a_case_without_a_grid_is_the_case():
    case = moorsolve.load_case(DOCK)
    assert inline_source(case) is case.source
    assert from_source(inline_source(case)) == case
