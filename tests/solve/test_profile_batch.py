"""A result's one-segment profiles drawn together (``moorsolve.solve.result.profile_batch``) are the
numbers each line's own drawing gives, bit for bit: grounded and hanging lines, with and
without seabed friction, inextensible, lines whose end A is the upper end (flipped), and a
touchdown that falls on a grid point (drawn alone)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from moorsolve import load_case, solve
from moorsolve.solve.result import profile_batch
from moorsolve.solve.result.profile_batch import ProfileBatch
from conftest import ROOT

CASES = ROOT / "cases"


def _profiles(case, monkeypatch=None):
    result = solve(case, solver="newton", audit=False)
    return [dict(leg.profile) for leg in result.legs]


def _alone(case, monkeypatch):
    with monkeypatch.context() as m:
        m.setattr(ProfileBatch, "add", lambda self, params, fallback, finish: fallback)
        return _profiles(case)


def _assert_same(together, alone):
    assert len(together) == len(alone)
    for a, b in zip(together, alone):
        assert a.keys() == b.keys()
        for key in a:
            assert np.array_equal(np.asarray(a[key]), np.asarray(b[key])), key


def _with_friction(case, mu):
    seabed = dataclasses.replace(case.environment.seabed, friction=mu)
    return dataclasses.replace(case, environment=dataclasses.replace(case.environment,
                                                                     seabed=seabed))


@pytest.mark.parametrize("name", ["floating_dock.yaml", "oc3_spar.yaml", "dock_quay.yaml",
                                  "check_failures.yaml", "three_platforms.yaml"])
def test_drawn_together_is_drawn_alone(name, monkeypatch):
    case = load_case(CASES / name)
    _assert_same(_profiles(case), _alone(case, monkeypatch))


def test_with_friction_and_inextensible(monkeypatch):
    case = _with_friction(load_case(CASES / "floating_dock.yaml"), 0.6)
    _assert_same(_profiles(case), _alone(case, monkeypatch))
    rigid = load_case({
        "environment": {"depth": 30.0, "seabed": {"friction": 0.5}},
        "line_types": {"chain": {"weight_in_water": 700.0}},        # inextensible
        "body": {"free": ["surge", "sway", "yaw"], "loads": {"force": [2e5, 5e4, 1e5]}},
        "legs": [{"name": f"L{k}", "anchor": [300.0 * np.cos(a), 300.0 * np.sin(a)],
                  "fairlead": [20.0 * np.cos(a), 20.0 * np.sin(a), 0.0],
                  "segments": [{"type": "chain", "length": 300.0}]}
                 for k, a in enumerate(np.radians([0.0, 120.0, 240.0]))]})
    _assert_same(_profiles(rigid), _alone(rigid, monkeypatch))


def test_flipped_lines_run_from_end_a(monkeypatch):
    """A line given fairlead first (end A high) is drawn from its lower end and turned."""
    case = load_case({
        "environment": {"depth": 50.0},
        "line_types": {"chain": {"weight_in_water": 900.0, "ea": 6e8}},
        "bodies": [{"name": "b", "free": []}],
        "points": [{"name": "anchor1", "position": [-300.0, 0.0]},
                   {"name": "anchor2", "position": [300.0, 10.0]}],
        "lines": [{"name": "down", "from": {"body": "b", "at": [-10.0, 0.0, -5.0]},
                   "to": "anchor1", "segments": [{"type": "chain", "length": 320.0}]},
                  {"name": "up", "from": "anchor2", "to": {"body": "b", "at": [10.0, 0.0, -5.0]},
                   "segments": [{"type": "chain", "length": 300.0}]}]})
    together = _profiles(case)
    assert together[0]["z_m"][0] > together[0]["z_m"][-1]       # end A is the upper end
    _assert_same(together, _alone(case, monkeypatch))


def test_a_touchdown_on_a_grid_point_is_drawn_alone(monkeypatch):
    calls = []
    real = profile_batch._arcs

    def on_grid(L, V, w, n):
        s, ok = real(L, V, w, n)
        calls.append(len(ok))
        return s, np.zeros_like(ok)          # as if every touchdown were on the grid

    case = load_case(CASES / "oc3_spar.yaml")
    with monkeypatch.context() as m:
        m.setattr(profile_batch, "_arcs", on_grid)
        together = _profiles(case)
    assert calls
    _assert_same(together, _alone(case, monkeypatch))


def test_the_audit_checks_profiles_drawn_together(monkeypatch):
    """A wrong profile from the joint drawing fails the profile audit inside ``solve``
    (``audit="full"``), and is refused when it is read from a result audited in closed
    form (which draws no profile)."""
    from moorsolve import ConvergenceError
    real = profile_batch._grounded

    def lifted(*args):
        planar = real(*args)
        return dict(planar, z=planar["z"] + 1.0)

    monkeypatch.setattr(profile_batch, "_grounded", lifted)
    case = load_case(CASES / "oc3_spar.yaml")
    with pytest.raises(ConvergenceError, match="independent audit"):
        solve(case, solver="newton", audit="full")
    result = solve(case, solver="newton")
    with pytest.raises(ConvergenceError, match="profile drawn from it fails the independent"):
        result.legs[0].profile["z_m"]
