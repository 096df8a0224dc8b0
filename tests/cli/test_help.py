"""The command line's own documentation: every option of every command is described in its
``--help``, the shared options say the same everywhere, and the solver defaults are explained
where they apply. Also: ``check`` on a berth of hawsers only prints no ``nan`` and no warning."""

from __future__ import annotations

import argparse
import math
import subprocess
import sys

import pytest

from moorsolve.cli import _parser
from conftest import ROOT


def _commands() -> dict:
    parser = _parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


COMMANDS = _commands()


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_every_option_is_described(name):
    """No option of any command is left without a help text."""
    for action in COMMANDS[name]._actions:
        if isinstance(action, argparse._HelpAction):
            continue
        assert action.help and action.help != argparse.SUPPRESS, \
            f"{name} {'/'.join(action.option_strings) or action.dest}: no help text"


@pytest.mark.parametrize("option", ["--tol", "--solver", "--allow-overload"])
def test_shared_options_say_the_same(option):
    """One definition: the help of a shared option is the same wherever it appears
    (the solver's up to the "default here" it names)."""
    helps = {}
    for name, parser in COMMANDS.items():
        for action in parser._actions:
            if option in action.option_strings:
                helps[name] = action.help.replace("default here: newton",
                                                  "default here: ipopt")
    assert len(helps) >= 3, helps
    assert len(set(helps.values())) == 1, helps


def test_solver_defaults_explained_in_each_help():
    """Every ``--solver`` says its own default and why sweep and envelope differ."""
    for name, parser in COMMANDS.items():
        action = next((a for a in parser._actions if "--solver" in a.option_strings), None)
        if action is None:
            continue
        assert f"default here: {action.default}" in action.help, name
        assert "sweep and envelope" in action.help and "for speed" in action.help, name
        expected = "newton" if name in ("sweep", "envelope") else "ipopt"
        assert action.default == expected, name


@pytest.mark.parametrize("name", [n for n, p in COMMANDS.items()
                                  if any("--tol" in a.option_strings for a in p._actions)])
def test_tol_described_in_help_output(name):
    """``--tol`` is explained in the printed help of every command that takes it."""
    text = " ".join(COMMANDS[name].format_help().split())
    assert "--tol TOL certified force residual relative to the largest line tension" in text


def test_check_hawsers_only_prints_no_nan():
    """A berth held only by hawsers (no mooring line): the mooring-line columns show "-",
    and nothing but the command's output reaches stderr (no plotting warning in --report)."""
    case = ROOT / "cases" / "ship_berth.yaml"
    proc = subprocess.run([sys.executable, "-m", "moorsolve.cli", "check", str(case),
                           "--no-damaged"], capture_output=True, text=True, cwd=ROOT,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "nan" not in proc.stdout.lower()
    row = next(line for line in proc.stdout.splitlines() if line.startswith("intact"))
    assert row.split()[2:7] == ["-"] * 5          # leg, T max, MBL/T, req, util
    assert "hawser breast_fwd" in proc.stdout       # the hawsers are checked below the table


def test_check_report_hawsers_only_no_warning(tmp_path):
    case = ROOT / "cases" / "ship_berth.yaml"
    out = tmp_path / "berth.html"
    proc = subprocess.run([sys.executable, "-m", "moorsolve.cli", "check", str(case),
                           "--no-damaged", "--report", str(out)], capture_output=True,
                          text=True, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == "", proc.stderr
    assert out.stat().st_size > 0


def test_utilisation_grid_has_hawser_columns():
    """The check report's utilisation picture draws the hawsers' columns."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from moorsolve import load_case
    from moorsolve.checks import run_checks
    from moorsolve.plot import utilisation_figure
    report = run_checks(load_case(ROOT / "cases" / "ship_berth.yaml"), damaged=False)
    fig = utilisation_figure(report)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_xticklabels()]
    hawsers = [i for i in report.conditions[0].items if i.check == "hawser tension"]
    assert labels == [i.leg for i in hawsers]
    cells = [t.get_text() for t in ax.texts]
    assert cells == [f"{i.utilisation:.2f}" for i in hawsers]
    assert all(math.isfinite(i.utilisation) for i in hawsers)
    plt.close(fig)


def test_plot_into_a_closed_pipe_is_not_a_traceback(tmp_path):
    """``moorsolve plot ... | head -0``: the reader went away; the picture is written and
    no traceback is printed."""
    case = ROOT / "cases" / "buoy_vida.yaml"
    out = tmp_path / "vida.png"
    proc = subprocess.run(f"{sys.executable} -m moorsolve.cli plot {case} -o {out} | head -c 0",
                          shell=True, capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert "Traceback" not in proc.stderr, proc.stderr
    assert out.read_bytes()[:4] == b"\x89PNG"
