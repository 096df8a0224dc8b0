"""Every example runs headless and says what it promises."""

import runpy
import sys
from conftest import ROOT


EXAMPLES = ROOT / "examples"


def run_example(name, argv, capsys, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setattr(sys, "argv", [name, *argv])
    runpy.run_path(str(EXAMPLES / name), run_name="__main__")
    return capsys.readouterr().out


def test_dock_typhoon_headings(tmp_path, capsys, monkeypatch):
    out = run_example("dock_typhoon_headings.py", ["--out", str(tmp_path)], capsys, monkeypatch)
    assert "worst case: load toward" in out
    # The dock is port-starboard symmetric: its worst heading is a beam load, 90 or 270.
    worst = out.split("worst case: load toward ")[1].split()[0]
    assert worst in ("90", "270")
    rows = [line.split() for line in out.splitlines()[1:] if line[:7].strip().isdigit()]
    assert len(rows) == 72
    assert max(float(r[5]) for r in rows) == float(out.split(" at ")[1].split()[0])
    png = tmp_path / "dock_typhoon_headings.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_buoy_vida_offset(tmp_path, capsys, monkeypatch):
    out = run_example("buoy_vida_offset.py", ["--out", str(tmp_path)], capsys, monkeypatch)
    rows = [line.split() for line in out.splitlines()[1:] if line.split()]
    bora_30 = next(r for r in rows if r[0] == "bora" and r[1] == "30.0")
    # At rest each chain holds Malacic's 528.5 N; under a 30 m/s bora the NNE chain
    # carries the most and the western one the least.
    rest = next(r for r in rows if r[0] == "bora" and r[1] == "0.0")
    assert rest[4] == "529"
    assert int(bora_30[4]) > int(bora_30[6]) > int(bora_30[8])
    # Jugo is bora mirrored about the east-west axis: the SSE chain takes the NNE's part.
    jugo_30 = next(r for r in rows if r[0] == "jugo" and r[1] == "30.0")
    assert (jugo_30[4], jugo_30[6], jugo_30[8]) == (bora_30[6], bora_30[4], bora_30[8])
    assert float(jugo_30[3]) == -float(bora_30[3])
    assert "largest offset:" in out
    png = tmp_path / "buoy_vida_offset.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_moordyn_roundtrip(tmp_path, capsys, monkeypatch):
    out = run_example("moordyn_roundtrip.py", ["--out", str(tmp_path)], capsys, monkeypatch)
    assert (tmp_path / "floating_dock.dat").exists()
    assert (tmp_path / "floating_dock_equilibrium.dat").exists()
    last = out.strip().splitlines()[-1].split()
    # "largest difference: offset X m, tension Y N": both solves and the held equilibrium agree.
    assert float(last[3]) < 1e-6 and float(last[6]) < 1e-2


def test_dock_chain_optimisation(tmp_path, capsys, monkeypatch):
    out = run_example("dock_chain_optimisation.py", ["--out", str(tmp_path)], capsys,
                      monkeypatch)
    assert "verified: True" in out
    assert "anchor uplift limit of 281 kN" in out and "would save" in out
    saved = float(out.split("chain saved: ")[1].split(" t")[0])
    assert saved > 0
    png = tmp_path / "dock_chain_optimisation.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cylinder_buoy_hydrodynamics(capsys, monkeypatch):
    # The example writes the table the shipped case carries, value for value.
    import yaml
    out = run_example("cylinder_buoy_hydrodynamics.py", [], capsys, monkeypatch)
    table = yaml.safe_load(out)["hydrodynamics"]
    case = yaml.safe_load((ROOT / "cases" / "buoy_sea.yaml").read_text())
    assert table == case["bodies"][0]["hydrodynamics"]


def test_box_dock_hydrodynamics(capsys, monkeypatch):
    # The example writes the table the shipped dock case carries, value for value.
    import yaml
    out = run_example("box_dock_hydrodynamics.py", [], capsys, monkeypatch)
    table = yaml.safe_load(out)["hydrodynamics"]
    case = yaml.safe_load((ROOT / "cases" / "dock_sea.yaml").read_text())
    assert table == case["bodies"][0]["hydrodynamics"]
