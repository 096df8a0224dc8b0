"""Sweeps at scale: the --set syntax, incremental output, resume, the CLI, Dask."""

import importlib
import io
import json
import os

import numpy as np
import pandas as pd
import pytest

import moorsolve
from moorsolve.cli import main
from moorsolve.errors import CaseError
from moorsolve.model.paths import parse_assignment, parse_values
from conftest import ROOT

sweep_module = importlib.import_module("moorsolve.studies.sweep_plan")
CASES = ROOT / "cases"
BUOY = CASES / "buoy_vida.yaml"
GRID = {"environment.wind.toward_deg": list(range(0, 360, 30)),
        "environment.wind.speed": [10.0, 20.0, 30.0]}
TENSIONS = [f"{leg}.{end}_tension_N" for leg in ("NNE", "SSE", "W")
            for end in ("fairlead", "anchor")]


# ---- the VALUES syntax ------------------------------------------------------------------


@pytest.mark.parametrize("text, values", [
    ("0,45,90", [0, 45, 90]),
    ("0:90:30", [0, 30, 60, 90]),                       # stop included when on the step
    ("0:100:30", [0, 30, 60, 90]),
    ("0:345:15", list(range(0, 360, 15))),
    ("0.1:0.5:0.1", [0.1, 0.2, 0.3, 0.4, 0.5]),
    ("5:-5:-5", [5, 0, -5]),
    ("10:30:10 kn", ["10 kn", "20 kn", "30 kn"]),
    ("10 kn,20 kn", ["10 kn", "20 kn"]),
    ("'0.5 m/s', 1.5", ["0.5 m/s", 1.5]),
    ("[1e5,0,0],[2e5, 0, 0]", [[1e5, 0, 0], [2e5, 0, 0]]),
    ("0:60:30,90", [0, 30, 60, 90]),
])
def test_values_syntax(text, values):
    assert parse_values(text, "f") == values


@pytest.mark.parametrize("text", ["1,,2", "[1,2", "1]", "0:10:0", "10:0:1", "1:2", "a:b:c",
                                  ""])
def test_bad_values_name_the_field(text):
    with pytest.raises(CaseError) as err:
        parse_values(text, "--set environment.wind.speed")
    assert err.value.field == "--set environment.wind.speed"


def test_assignment_needs_path_and_values():
    assert parse_assignment("legs[*].segments[0].length=48,50") == (
        "legs[*].segments[0].length", [48, 50])
    with pytest.raises(CaseError, match="PATH=VALUES"):
        parse_assignment("environment.wind.speed")


# ---- incremental output and resume --------------------------------------------------------


class _Interrupted(Exception):
    pass


def _interrupt_after(monkeypatch, n_chunks):
    real = sweep_module.SweepPlan.solve_chunk
    calls = []

    def solve_chunk(self, points):
        if len(calls) == n_chunks:
            raise _Interrupted()
        calls.append(len(points))
        return real(self, points)

    monkeypatch.setattr(sweep_module.SweepPlan, "solve_chunk", solve_chunk)


@pytest.mark.parametrize("ext", [".csv", ".parquet"])
def test_a_resumed_sweep_equals_an_uninterrupted_one(tmp_path, monkeypatch, ext):
    case = moorsolve.load_case(BUOY)
    whole = tmp_path / f"whole{ext}"
    part = tmp_path / f"part{ext}"
    full = moorsolve.sweep(case, GRID, output=whole, chunk_size=5, workers=1)
    assert list(full.index) == list(range(36))
    assert json.loads((tmp_path / f"whole{ext}.sweep.json").read_text())["complete"]

    _interrupt_after(monkeypatch, 3)
    with pytest.raises(_Interrupted):
        moorsolve.sweep(case, GRID, output=part, chunk_size=5, workers=1)
    record = json.loads((tmp_path / f"part{ext}.sweep.json").read_text())
    assert record["complete"] is False
    if ext == ".csv":
        rows = pd.read_csv(part, index_col="point")
        assert len(rows) == 15                            # three chunks kept, flushed
        with open(part, "a") as f:
            f.write("31,300.0,30.0,Tr")                   # torn by the interruption
    else:
        assert not part.exists()
        parts = list((tmp_path / "part.parquet.parts").glob("part-*.parquet"))
        assert sum(len(pd.read_parquet(p)) for p in parts) == 15

    monkeypatch.undo()
    calls = []
    real = sweep_module.SweepPlan.solve_chunk
    monkeypatch.setattr(sweep_module.SweepPlan, "solve_chunk",
                        lambda self, pts: calls.append(len(pts)) or real(self, pts))
    resumed = moorsolve.sweep(case, GRID, output=part, resume=True, chunk_size=5, workers=1)
    assert sum(calls) == 36 - 15                          # only the missing points
    pd.testing.assert_frame_equal(resumed, full)
    if ext == ".csv":
        assert part.read_bytes() == whole.read_bytes()
    else:
        pd.testing.assert_frame_equal(pd.read_parquet(part), pd.read_parquet(whole))
        assert not (tmp_path / "part.parquet.parts").exists()
    # Resuming a finished file solves nothing.
    calls.clear()
    again = moorsolve.sweep(case, GRID, output=part, resume=True, chunk_size=5)
    assert calls == [] and len(again) == 36


def test_file_rows_equal_the_in_memory_sweep(tmp_path):
    case = moorsolve.load_case(BUOY)
    grid = {"environment.wind.speed": ["10 kn", 20.0],
            "body.loads.force": [[1e3, 0, 0], [0, 2e3, 0]]}
    mem = moorsolve.sweep(case, grid)
    speed = "environment.wind.speed [m/s]"
    force = ["body.loads.force[0] [N]", "body.loads.force[1] [N]", "body.loads.force[2] [N m]"]
    assert mem.index.name == "point" and list(mem.columns[:4]) == [speed] + force
    knot = 1852.0 / 3600.0
    assert list(mem[speed]) == pytest.approx([10 * knot, 10 * knot, 20.0, 20.0], rel=1e-12)
    assert mem[force].to_numpy().tolist() == [[1e3, 0, 0], [0, 2e3, 0]] * 2
    for ext in (".csv", ".parquet"):
        out = moorsolve.sweep(case, grid, output=tmp_path / f"r{ext}")
        # In a file as in memory: numbers in SI, one column per list item.
        np.testing.assert_array_equal(out[[speed] + force].to_numpy(),
                                      mem[[speed] + force].to_numpy())
        np.testing.assert_array_equal(out[TENSIONS].to_numpy(), mem[TENSIONS].to_numpy())
        assert list(out["reason"]) == list(mem["reason"])


def test_progress_bar_counts_points():
    buf = io.StringIO()
    moorsolve.sweep(moorsolve.load_case(BUOY), GRID, progress=buf)
    assert "36/36" in buf.getvalue()


def test_existing_output_is_not_overwritten_silently(tmp_path):
    case = moorsolve.load_case(BUOY)
    out = tmp_path / "r.csv"
    out.write_text("precious\n")
    with pytest.raises(CaseError, match="--resume"):
        moorsolve.sweep(case, GRID, output=out)
    assert out.read_text() == "precious\n"
    with pytest.raises(CaseError, match="no sweep record"):
        moorsolve.sweep(case, GRID, output=out, resume=True)
    moorsolve.sweep(case, GRID, output=out, overwrite=True)
    assert len(pd.read_csv(out)) == 36


# ---- the command line ------------------------------------------------------------------------


def _sweep_cli(tmp_path, *extra, out="r.csv"):
    return main(["sweep", str(BUOY), "--set", "environment.wind.toward_deg=0:330:30",
                 "--set", "environment.wind.speed=10:30:10", "-o", str(tmp_path / out),
                 *extra])


def test_cli_sweep_writes_the_grid(tmp_path, capsys):
    assert _sweep_cli(tmp_path) == 0
    assert "36 points" in capsys.readouterr().out
    table = pd.read_csv(tmp_path / "r.csv", index_col="point")
    ref = moorsolve.sweep(moorsolve.load_case(BUOY), GRID)
    np.testing.assert_array_equal(table["environment.wind.toward_deg [deg]"],
                                  ref["environment.wind.toward_deg [deg]"])
    np.testing.assert_allclose(table[TENSIONS], ref[TENSIONS], rtol=1e-9)
    # A finished file resumes to itself; another grid or case is refused.
    before = (tmp_path / "r.csv").read_bytes()
    assert _sweep_cli(tmp_path, "--resume") == 0
    assert (tmp_path / "r.csv").read_bytes() == before
    code = main(["sweep", str(BUOY), "--set", "environment.wind.toward_deg=0:330:30",
                 "--set", "environment.wind.speed=10:40:10", "-o", str(tmp_path / "r.csv"),
                 "--resume"])
    assert code == 2
    assert "--resume" in capsys.readouterr().err
    code = main(["sweep", str(CASES / "buoy_vida_current.yaml"),
                 "--set", "environment.wind.toward_deg=0:330:30",
                 "--set", "environment.wind.speed=10:30:10", "-o", str(tmp_path / "r.csv"),
                 "--resume"])
    assert code == 2
    assert "different case" in capsys.readouterr().err
    assert (tmp_path / "r.csv").read_bytes() == before


def test_cli_sweep_with_failed_points_writes_every_row_and_exits_1(tmp_path, capsys):
    # 100 MN pulls Vida's 50 m chains straight: no equilibrium, a row with the reason.
    code = main(["sweep", str(BUOY), "--set", "body.loads.force=[1e3,0,0],[1e8,0,0]",
                 "-o", str(tmp_path / "f.csv")])
    assert code == 1
    assert "1 of 2 points have no certified equilibrium" in capsys.readouterr().err
    table = pd.read_csv(tmp_path / "f.csv", index_col="point")
    assert list(table["converged"]) == [True, False]
    assert "pulled straight" in table["reason"][1]


@pytest.mark.parametrize("argv, field", [
    (["--set", "environment.wind.sped=1,2"], "--set environment.wind.sped"),
    (["--set", "environment.wind.speed=1,-2"], "--set environment.wind.speed"),
    (["--set", "environment.wind.speed"], "--set"),
    (["--set", "environment.wind.speed=0:10:0"], "--set environment.wind.speed"),
    (["--set", "legs[Q].anchor=[0,0]"], "--set legs[Q].anchor"),
    (["--set", "environment.wind.speed=1", "--set", "environment.wind.speed=2"],
     "--set environment.wind.speed"),
    (["--set", "environment.wind.speed=1", "--scheduler", "localhost"], "--scheduler"),
])
def test_cli_bad_sweeps_exit_2_and_write_nothing(tmp_path, capsys, argv, field):
    for out in ("r.csv", "r.parquet"):
        code = main(["sweep", str(BUOY), *argv, "-o", str(tmp_path / out)])
        err = capsys.readouterr().err
        assert code == 2
        assert err.count("\n") == 1 and "Traceback" not in err
        assert err.startswith(f"moorsolve: bad input: {field}")
    assert os.listdir(tmp_path) == []


def test_cli_bad_output_extension(tmp_path, capsys):
    assert main(["sweep", str(BUOY), "--set", "environment.wind.speed=1",
                 "-o", str(tmp_path / "r.txt")]) == 2
    assert capsys.readouterr().err.startswith("moorsolve: bad input: --output")
    assert os.listdir(tmp_path) == []


# ---- Dask ------------------------------------------------------------------------------------


@pytest.fixture
def worker_path(monkeypatch):
    """Worker processes import this checkout's moorsolve, as the test process does."""
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))


def _dock_grid():
    heading = ("environment.wind.toward_deg", "environment.current.toward_deg",
               "environment.waves.toward_deg")
    return {heading: [(h, h, h) for h in range(0, 360, 20)],
            "environment.wind.speed": [20.0, 30.0, 40.0, 50.0]}


def test_dask_processes_equal_the_local_run(tmp_path, worker_path):
    distributed = pytest.importorskip("distributed")
    case = moorsolve.load_case(CASES / "floating_dock.yaml")
    grid = _dock_grid()
    local = moorsolve.sweep(case, grid, chunk_size=8)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            files = set(client.run(lambda: __import__("moorsolve").__file__).values())
            assert files == {moorsolve.__file__}
        out = tmp_path / "dask.parquet"
        remote = moorsolve.sweep(case, grid, chunk_size=8, output=out,
                                 scheduler=cluster.scheduler_address)
    assert local["converged"].all()
    cols = [c for c in local.columns if c.endswith("tension_N")]
    np.testing.assert_allclose(remote[cols].to_numpy(), local[cols].to_numpy(), rtol=1e-9)
    np.testing.assert_allclose(remote[["x_m", "y_m", "yaw_deg"]].to_numpy(),
                               local[["x_m", "y_m", "yaw_deg"]].to_numpy(), rtol=1e-9,
                               atol=1e-12)
    assert list(remote.index) == list(range(len(local)))


def test_dask_threads_client_and_slow_path(tmp_path):
    distributed = pytest.importorskip("distributed")
    case = moorsolve.load_case(BUOY)
    # Gravity changes the problem's structure: full IPOPT solves on the workers.
    grid = {"environment.gravity": [9.81, 9.7], "environment.wind.speed": [10.0, 30.0]}
    local = moorsolve.sweep(case, grid, chunk_size=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  protocol="tcp://", host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = moorsolve.sweep(case, grid, scheduler=client, output=tmp_path / "r.csv",
                                     chunk_size=2)
    assert set(remote["solver"]) == {"ipopt"}
    np.testing.assert_allclose(remote[TENSIONS].to_numpy(), local[TENSIONS].to_numpy(),
                               rtol=1e-9)


def test_grid_columns_are_si_numbers_named_with_their_unit(tmp_path, capsys):
    # The command line's "10:20:10 kn" is two speeds in knots: m/s in the file.
    assert main(["sweep", str(BUOY), "--set", "environment.wind.speed=10:20:10 kn",
                 "--set", "legs[*].segments[0].length=50 m,5000 cm",
                 "-o", str(tmp_path / "u.csv")]) == 0
    table = pd.read_csv(tmp_path / "u.csv", index_col="point")
    knot = 1852.0 / 3600.0
    np.testing.assert_allclose(table["environment.wind.speed [m/s]"],
                               [10 * knot, 10 * knot, 20 * knot, 20 * knot], rtol=1e-12)
    np.testing.assert_array_equal(table["legs[*].segments[0].length [m]"], [50.0] * 4)
    # A value that is not a quantity keeps its path as the name and is text in a file.
    mem = moorsolve.sweep(moorsolve.load_case(BUOY), {"body.free": [["surge", "sway"],
                                                                    ["surge"]]})
    assert list(mem["body.free"]) == [["surge", "sway"], ["surge"]]
