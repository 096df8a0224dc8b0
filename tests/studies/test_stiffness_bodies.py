"""The stiffness of every body of a scene, the others held at their solved poses, against
central differences of re-solved poses (tests/studies/resolved.py)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import moorsolve
from moorsolve.cli import main

from edge_scenes import calm_and_tanker
from resolved import assert_matrix_close, resolved_stiffness

CASES = Path(__file__).resolve().parents[2] / "cases"


@pytest.fixture(scope="module")
def platforms():
    return moorsolve.solve(moorsolve.load_case(CASES / "three_platforms.yaml"))


@pytest.mark.parametrize("body", ["west", "middle", "east"])
def test_each_platform_of_three_on_shared_lines(platforms, body):
    """Each platform's own 6x6 (bridles to free apexes, shared chains to its neighbours,
    which stay where they are) equals the re-solved one; before, only the first body's
    wrench was differentiated (east all zeros, middle K11 -2168 N/m)."""
    K = moorsolve.stiffness(platforms, body=body)
    assert_matrix_close(K, resolved_stiffness(platforms, body), label=body)
    assert K[0, 0] > 0 and K[1, 1] > 0


def test_tanker_on_a_hawser_to_a_calm_buoy():
    """The tanker's stiffness has the sign of a restoring force: along the taut hawser it
    is the elastic bar's ``EA/L`` in series with the buoy held (re-solved reference);
    the buoy's includes the hawser pulling it."""
    result = moorsolve.solve(moorsolve.load_case(calm_and_tanker()))
    for body in ("buoy", "tanker"):
        K = moorsolve.stiffness(result, body=body)
        assert_matrix_close(K, resolved_stiffness(result, body), label=body)
    K = moorsolve.stiffness(result, body="tanker")
    hawser = result.leg("hawser")
    ea, length = 5.0e7, 60.0
    stretched = length * (1 + hawser.fairlead_tension_N / ea)
    # Nearly along x: the bar's axial stiffness EA/L, plus nothing else to first order.
    assert K[0, 0] == pytest.approx(ea / length, rel=0.05)
    assert K[0, 0] > 0
    assert K[1, 1] == pytest.approx(hawser.fairlead_tension_N / stretched, rel=0.05)


def test_cli_names_the_held_bodies(capsys):
    status = main(["stiffness", str(CASES / "three_platforms.yaml"), "--body", "east",
                   "--json"])
    assert status == 0
    out = json.loads(capsys.readouterr().out)
    assert out["body"] == "east" and out["held_bodies"] == ["west", "middle"]
    assert out["about"] == "solved poses"
    assert np.asarray(out["matrix"])[0, 0] > 0
    status = main(["stiffness", str(CASES / "three_platforms.yaml"), "--body", "middle"])
    text = capsys.readouterr().out
    assert status == 0 and "west, east held at their solved poses" in text
