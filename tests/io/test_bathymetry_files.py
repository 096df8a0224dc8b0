"""Bathymetry files (issue 19, item 3): MoorDyn's SeafloorFile (MoorDyn-F and MoorDyn-C
forms), CSV and NetCDF grids named in a case file, read relative to it; their errors."""

import os

import numpy as np
import pytest
import yaml

from moorsolve import load_case
from moorsolve.cli import main
from moorsolve.errors import CaseError
from moorsolve.io.bathymetry import read_bathymetry, seafloor_text

FIELD = "environment.seabed.bathymetry"
X = [-50.0, 0.0, 100.0]
Y = [-20.0, 30.0]
DEPTH = [[40.0, 41.0, 43.0], [42.0, 44.5, 47.0]]


def _case(seabed) -> dict:
    return {"environment": {"depth": 40.0, "seabed": seabed},
            "line_types": {"chain": {"weight_in_water": 1000.0, "ea": 5e8}},
            "legs": [{"name": "A", "anchor": [-40.0, 0.0], "fairlead": [60.0, 5.0, -5.0],
                      "segments": [{"type": "chain", "length": 130}]}]}


def _write_moordyn_f(path):
    path.write_text("--- MoorDyn bathymetry ---\nnGridX 3\nnGridY 2\n"
                    "  -50 0 100\n-20 40 41 43\n 30 42 44.5 47\n")


def test_seafloor_file_of_moordyn_f_and_moorpy(tmp_path):
    path = tmp_path / "bath.txt"
    _write_moordyn_f(path)
    assert read_bathymetry(path) == {"x": X, "y": Y, "depth": DEPTH}


def test_seafloor_file_of_moordyn_c(tmp_path):
    # MoorDyn-C: counts, the axes, then x y z rows (z the seabed's height, any order).
    path = tmp_path / "bath_c.txt"
    rows = [f"{x:g} {y:g} {-d:g}" for y, ds in zip(Y, DEPTH) for x, d in zip(X, ds)][::-1]
    path.write_text("3 2\n-50 0 100\n-20 30\n" + "\n".join(rows) + "\n")
    assert read_bathymetry(path) == {"x": X, "y": Y, "depth": DEPTH}


def test_csv_in_any_row_and_column_order(tmp_path):
    rows = [f"{d},{x},{y}" for y, ds in zip(Y, DEPTH) for x, d in zip(X, ds)]
    path = tmp_path / "bath.csv"
    path.write_text("depth,x,y\n" + "\n".join(reversed(rows)) + "\n")
    assert read_bathymetry(path) == {"x": X, "y": Y, "depth": DEPTH}


def test_written_seafloor_file_reads_back(tmp_path):
    case = load_case(_case({"bathymetry": {"x": X, "y": Y, "depth": DEPTH}}))
    path = tmp_path / "out.txt"
    path.write_text(seafloor_text(case.environment.seabed.bathymetry))
    assert read_bathymetry(path) == {"x": X, "y": Y, "depth": DEPTH}


def test_netcdf_grid(tmp_path):
    xarray = pytest.importorskip("xarray")
    path = tmp_path / "bath.nc"
    ds = xarray.Dataset({"depth": (("y", "x"), np.array(DEPTH))}, coords={"x": X, "y": Y})
    try:
        ds.to_netcdf(path)
    except (ValueError, ImportError) as exc:
        pytest.skip(f"no NetCDF backend: {exc}")
    assert read_bathymetry(path) == {"x": X, "y": Y, "depth": DEPTH}
    # Heights positive up under the name z.
    path_z = tmp_path / "bath_z.nc"
    xarray.Dataset({"z": (("x", "y"), -np.array(DEPTH).T)}, coords={"x": X, "y": Y}
                   ).to_netcdf(path_z)
    assert read_bathymetry(path_z) == {"x": X, "y": Y, "depth": DEPTH}


def test_netcdf_without_xarray_names_the_field(tmp_path, monkeypatch):
    import builtins
    real = builtins.__import__

    def no_xarray(name, *args, **kwargs):
        if name == "xarray":
            raise ImportError("no xarray")
        return real(name, *args, **kwargs)
    monkeypatch.setattr(builtins, "__import__", no_xarray)
    with pytest.raises(CaseError, match="needs xarray") as err:
        read_bathymetry(tmp_path / "bath.nc")
    assert err.value.field == FIELD


def test_a_case_file_reads_its_grid_relative_to_itself(tmp_path, monkeypatch):
    folder = tmp_path / "site"
    folder.mkdir()
    _write_moordyn_f(folder / "bath.txt")
    (folder / "case.yaml").write_text(yaml.safe_dump(_case({"bathymetry": "bath.txt"})))
    monkeypatch.chdir(tmp_path)                       # not the case file's folder
    case = load_case(folder / "case.yaml")
    grid = case.environment.seabed.bathymetry
    assert grid.x == tuple(X) and grid.depth[1] == tuple(DEPTH[1])
    assert grid.source == str(folder / "bath.txt") and "3 x 2 nodes" in repr(grid)
    # The anchor given as [x, y] sits on the interpolated surface: at (-40, 0), fx = 0.2,
    # fy = 0.4: 40*0.8*0.6 + 41*0.2*0.6 + 42*0.8*0.4 + 44.5*0.2*0.4 = 41.12 m deep.
    assert case.lines[0].a.position[2] == pytest.approx(-41.12, abs=1e-12)
    # The source keeps the file's absolute name: a sweep's copy loads from anywhere.
    kept = case.source["environment"]["seabed"]["bathymetry"]
    assert os.path.isabs(kept)
    monkeypatch.chdir(folder.parent.parent)
    assert load_case(case.source).environment.seabed.bathymetry == grid


@pytest.mark.parametrize("name, text, words", [
    ("b.txt", "header\nnGridX 3\nnGridY 2\n-50 0\n-20 1 2 3\n30 1 2 3\n", "2 x values"),
    ("b.txt", "header\nnGridZ 3\nnGridY 2\n", "nGridX"),
    ("b.txt", "header\nnGridX 3\nnGridY 2\n-50 0 100\n-20 1 2 3\n", "1 rows of depths"),
    ("b.txt", "header\nnGridX 3\nnGridY 1\n-50 0 100\n-20 1 x 3\n", "'x' is not a number"),
    ("b.txt", "header\nnGridX 3\nnGridY 1\n-50 0 100\n-20 1 2\n", "a row is y then 3"),
    ("b.csv", "x,y,z\n1,2,3\n", "three columns x, y, depth"),
    ("b.csv", "x,y,depth\n0,0,1\n1,0,1\n0,1,1\n", "(1, 1) is missing"),
    ("b.csv", "x,y,depth\n0,0,1\n0,0,2\n", "appears twice"),
    ("b.txt", "2 1\n0 1\n0\n0 0 -5\n", "1 grid nodes have no depth"),
])
def test_file_errors_name_the_field_file_and_line(tmp_path, name, text, words):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(CaseError) as err:
        load_case(_case({"bathymetry": str(path)}))
    assert err.value.field == FIELD
    assert words in str(err.value) and name in str(err.value)


def test_grid_values_are_validated_after_reading(tmp_path):
    path = tmp_path / "b.txt"
    path.write_text("header\nnGridX 2\nnGridY 1\n5 0\n0 10 20\n")
    with pytest.raises(CaseError, match="strictly increasing") as err:
        load_case(_case({"bathymetry": str(path)}))
    assert err.value.field == FIELD + ".x[1]"


def test_cli_exits_2_on_a_missing_grid_file(tmp_path, capsys):
    (tmp_path / "case.yaml").write_text(yaml.safe_dump(_case({"bathymetry": "nowhere.txt"})))
    assert main(["solve", str(tmp_path / "case.yaml")]) == 2
    err = capsys.readouterr().err
    assert FIELD in err and "not found" in err
