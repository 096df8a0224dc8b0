"""Every example runs headless and says what it promises."""

import pathlib
import runpy
import sys


EXAMPLES = pathlib.Path(__file__).resolve().parent.parent / "examples"


def run_example(name, argv, capsys, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setattr(sys, "argv", [name, *argv])
    runpy.run_path(str(EXAMPLES / name), run_name="__main__")
    return capsys.readouterr().out


def test_dock_typhoon_headings(tmp_path, capsys, monkeypatch):
    out = run_example("dock_typhoon_headings.py", ["--out", str(tmp_path)], capsys, monkeypatch)
    assert "worst case: load toward" in out
    png = tmp_path / "dock_typhoon_headings.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_buoy_vida_offset(capsys, monkeypatch):
    out = run_example("buoy_vida_offset.py", [], capsys, monkeypatch)
    rows = [line.split() for line in out.splitlines()[1:]]
    bora_30 = next(r for r in rows if r[0] == "bora" and r[1] == "30.0")
    # At rest each chain holds Malacic's 528.5 N; under a 30 m/s bora the NNE chain
    # carries the most and the western one the least.
    rest = next(r for r in rows if r[0] == "bora" and r[1] == "0.0")
    assert rest[4] == "529"
    assert int(bora_30[4]) > int(bora_30[6]) > int(bora_30[8])


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
