"""The fast paths of a solve give the answer of the slow ones (issue 16).

Each speed-up is checked against the code it replaces or the reference it shortens:
the compiled kernel's stiffness and stability test against the condensation and
eigenvalues in Python, the Newton fast path against IPOPT over seeded random loads, lazy
legs and profiles against the physics they draw, and the per-case and per-geometry
memos against fresh solves (they must never serve a stale answer).
"""

from __future__ import annotations

import dataclasses
import math
import threading

import numpy as np
import pytest

import moorsolve
from moorsolve.model import BodyLoads
from moorsolve.model import shared as shared_parts
from moorsolve.solve.assembly import prepared
from moorsolve.solve.assembly.cache import get_problem, problem_key
from moorsolve.solve.result.diagnosis import over_mbl
from moorsolve.solve.equilibrium import rest_point
from moorsolve.solve.result.classes import DeferredStability
from moorsolve.solve.stability.static import assess, condensed_stiffness
from moorsolve.solve.kernels.start import scales

from conftest import CASES

DOCK = CASES / "floating_dock.yaml"
SPAR = CASES / "oc3_spar.yaml"
SHIP = CASES / "turret_ship.yaml"


def with_force(case, force):
    """``case`` with its first body's loads replaced by a constant ``force`` (3 or 6)."""
    env = dataclasses.replace(case.environment, wind=None, current=None, waves=None)
    body = dataclasses.replace(case.bodies[0], loads=BodyLoads(force=tuple(force)))
    return dataclasses.replace(case, environment=env, bodies=(body,))


def random_loads(n, max_force, max_moment, six=False, seed=16):
    rng = np.random.default_rng(seed)
    loads = []
    for _ in range(n):
        f, a = rng.uniform(0, max_force), rng.uniform(0, 2 * math.pi)
        m = rng.uniform(-max_moment, max_moment)
        loads.append((f * math.cos(a), f * math.sin(a), 0.0, 0.0, 0.0, m) if six
                     else (f * math.cos(a), f * math.sin(a), m))
    return loads


def largest_tension(result):
    return max(max(leg.fairlead_tension_N, leg.anchor_tension_N) for leg in result.legs)


def assert_same_answer(a, b, tol):
    """Two certified results of one case agree to the certificate's tolerance: every end
    tension within ``tol`` of the largest, every body pose to the same relative size."""
    scale = largest_tension(a)
    for la, lb in zip(a.legs, b.legs):
        for field in ("fairlead_tension_N", "anchor_tension_N", "horizontal_tension_N",
                      "fairlead_vertical_N", "anchor_vertical_N", "grounded_length_m"):
            assert abs(getattr(la, field) - getattr(lb, field)) <= tol * scale, (la.name, field)
    for ba, bb in zip(a.bodies, b.bodies):
        for key in ("x_m", "y_m", "z_m"):
            assert bb[key] == pytest.approx(ba[key], abs=1e-6)
        for key in ("roll_deg", "pitch_deg", "yaw_deg"):
            assert bb[key] == pytest.approx(ba[key], abs=1e-6)


# ---- the kernel's stiffness and stability test ------------------------------------------


@pytest.mark.parametrize("path,force", [(DOCK, (1e6, 2e6, 1e7)),
                                        (SPAR, (6e5, -2e5, 0, 0, 0, 1e6)),
                                        (SHIP, None)], ids=["dock", "spar", "ship"])
def test_kernel_stiffness_is_the_condensed_stiffness(path, force):
    case = moorsolve.load_case(path)
    if force is not None:
        case = with_force(case, force)
    result = moorsolve.solve(case, solver="newton")
    problem = get_problem(case)
    p = problem.parameters(case)
    with problem.lock:
        post = problem.post(result.state, p)
    K, _ = condensed_stiffness(problem, result.state, p)
    np.testing.assert_allclose(post["stiffness"], K, rtol=1e-9,
                               atol=1e-9 * np.max(np.abs(K)))


@pytest.mark.parametrize("path,six,max_force,max_moment", [
    (DOCK, False, 8e6, 5e7), (SPAR, True, 1.5e6, 5e6)], ids=["dock", "spar"])
def test_kernel_stability_test_agrees_with_the_eigenvalues(path, six, max_force, max_moment):
    """Where the kernel calls a point clearly stable, the eigenvalues computed in Python
    say stable too, and the reported eigenvalues are theirs."""
    base = moorsolve.load_case(path)
    flagged = 0
    for load in random_loads(12, max_force, max_moment, six=six):
        case = with_force(base, load)
        try:
            result = moorsolve.solve(case, solver="newton")
        except moorsolve.ConvergenceError:
            continue
        problem = get_problem(case)
        reference = assess(problem, result.state, problem.parameters(case))
        assert result.stability.stable == reference.stable
        if isinstance(result.stability, DeferredStability):
            flagged += 1
            assert reference.stable
            np.testing.assert_allclose(sorted(np.real(result.stability.eigenvalues)),
                                       sorted(np.real(reference.eigenvalues)), rtol=1e-8)
            assert result.stability.min_eigenvalue == pytest.approx(
                reference.min_eigenvalue, rel=1e-8)
            assert result.to_dict()["stability"]["min_eigenvalue"] > 0
    assert flagged >= 6


@pytest.mark.parametrize("path,six,max_force,max_moment", [
    (DOCK, False, 8e6, 5e7), (SPAR, True, 1.5e6, 5e6)], ids=["dock", "spar"])
def test_kernel_batch_is_the_kernel_point_by_point(path, six, max_force, max_moment):
    """A load table's batch (NewtonKernel.run_many) returns, row by row, what one run of
    the kernel returns; its stability flag is the post function's test at that point."""
    base = moorsolve.load_case(path)
    cases = [with_force(base, load) for load in random_loads(8, max_force, max_moment, six)]
    problem = get_problem(cases[0])
    kernel = problem.newton()
    assert kernel.wait_compiled(300)
    x_rest = rest_point(problem, cases[0], 1e-9, kernel)
    P = np.array([problem.parameters(c) for c in cases])
    batch = kernel.run_many(x_rest, P, 1e-9)
    names = ("x", "status", "iterations", "certificate", "body", "fairlead_tension",
             "anchor_tension", "reactions", "clearly_stable")
    for row, p in enumerate(P):
        single = [np.array(v) for v in kernel.raw(x_rest, p, 1e-9)]
        for name, value in zip(names, single):
            np.testing.assert_array_equal(batch[name][row], value, err_msg=name)
        post = kernel.post(batch["x"][row], p)
        assert batch["clearly_stable"][row, 0] == post["clearly_stable"].item()


def test_unstable_point_still_reaches_the_full_check():
    """The turret ship held stern to the wind is unstable: the kernel's test must not call
    it stable, so the solve still finds the stable heading (tests/test_network.py)."""
    case = moorsolve.load_case(SHIP)
    for solver in ("newton", "ipopt"):
        result = moorsolve.solve(case, solver=solver)
        assert result.stability.stable
        assert not isinstance(result.stability, DeferredStability) or \
            result.stability.min_eigenvalue > 0


# ---- Newton against IPOPT over random loads ------------------------------------------------


@pytest.mark.parametrize("path,six,max_force,max_moment,n", [
    (DOCK, False, 9e6, 8e7, 25), (SPAR, True, 1.5e6, 5e6, 15)], ids=["dock", "spar"])
def test_newton_full_result_equals_ipopt_over_random_loads(path, six, max_force, max_moment,
                                                           n):
    base = moorsolve.load_case(path)
    tol = 1e-9
    compared = 0
    for load in random_loads(n, max_force, max_moment, six=six, seed=7):
        case = with_force(base, load)
        try:
            ref = moorsolve.solve(case, solver="ipopt", tol=tol)
        except moorsolve.ConvergenceError:
            with pytest.raises(moorsolve.ConvergenceError):
                moorsolve.solve(case, solver="newton", tol=tol)
            continue
        fast = moorsolve.solve(case, solver="newton", tol=tol)
        assert fast.converged and fast.certificate.relative <= tol
        assert_same_answer(ref, fast, 1e-7)
        a, b = (r.to_dict(profiles=False)["stability"] for r in (ref, fast))
        assert b.pop("min_eigenvalue") == pytest.approx(a.pop("min_eigenvalue"), rel=1e-6)
        assert a == b
        compared += 1
    assert compared >= n // 2


def test_held_body_on_three_lines_newton_equals_ipopt():
    spar = moorsolve.load_case(SPAR)
    held = dataclasses.replace(spar, bodies=(dataclasses.replace(spar.bodies[0], free=()),))
    for load in random_loads(5, 1e6, 1e6, six=True, seed=3):
        case = with_force(held, load)
        assert_same_answer(moorsolve.solve(case), moorsolve.solve(case, solver="newton"),
                           1e-9)


def test_held_body_lines_state_is_remembered_and_never_stale():
    """With nothing free no body load moves a fairlead: the lines' state a solve certified
    is remembered per geometry, so later solves certify it as it stands (no solver
    called); the first solve reports its own solver's work, and a geometry change (the
    body held elsewhere) solves afresh."""
    from moorsolve.solve.result.diagnosis import START_CERTIFIED
    spar = moorsolve.load_case(SPAR)

    def held_at(dx):      # a geometry of this test's own: none solved before it
        body = spar.bodies[0]
        return dataclasses.replace(spar, bodies=(dataclasses.replace(
            body, free=(), position=(body.position[0] + dx, *body.position[1:])),))

    held = held_at(1.25)
    fresh = moorsolve.solve(with_force(held, (1e5, 0, 0, 0, 0, 0)))
    assert fresh.certificate.iterations > 0 and fresh.certificate.status != START_CERTIFIED
    for load in random_loads(3, 1e6, 1e6, six=True, seed=5):
        for solver in ("ipopt", "newton"):
            result = moorsolve.solve(with_force(held, load), solver=solver)
            assert result.certificate.iterations == 0 and result.solver == solver
            assert result.certificate.status == START_CERTIFIED
            assert_same_answer(fresh, result, 1e-12)
    elsewhere = with_force(held_at(6.25), (1e5, 0, 0, 0, 0, 0))
    newton = moorsolve.solve(elsewhere, solver="newton")
    assert newton.certificate.iterations > 0
    assert all(a.fairlead_tension_N != pytest.approx(b.fairlead_tension_N, rel=1e-3)
               for a, b in zip(newton.legs, fresh.legs))
    assert_same_answer(newton, moorsolve.solve(elsewhere, solver="ipopt"), 1e-9)


def test_held_body_in_a_current_on_lumped_lines_is_never_served_a_stale_state():
    """The current moves lumped lines: each current has its own remembered state, and a
    state remembered under one current never answers another."""
    case = moorsolve.load_case(CASES / "buoy_vida_current.yaml")
    held = dataclasses.replace(case, bodies=(dataclasses.replace(case.bodies[0], free=()),))

    def in_current(scale):
        cur = held.environment.current
        flow = dataclasses.replace(cur, speed=cur.speed * scale,
                                   profile=tuple((z, v * scale) for z, v in cur.profile))
        return dataclasses.replace(held, environment=dataclasses.replace(
            held.environment, current=flow))

    first = {scale: moorsolve.solve(in_current(scale)) for scale in (1.3, 2.1)}
    assert first[1.3].legs[0].fairlead_tension_N != pytest.approx(
        first[2.1].legs[0].fairlead_tension_N, rel=1e-4)
    for scale in (2.1, 1.3, 2.1):
        for solver in ("newton", "ipopt"):
            result = moorsolve.solve(in_current(scale), solver=solver)
            assert result.converged
            assert_same_answer(first[scale], result, 1e-9)


def test_held_body_solves_from_many_threads_share_one_remembered_state():
    spar = moorsolve.load_case(SPAR)
    body = spar.bodies[0]
    held = dataclasses.replace(spar, bodies=(dataclasses.replace(
        body, free=(), position=(body.position[0] - 2.5, *body.position[1:])),))
    loads = random_loads(16, 1e6, 1e6, six=True, seed=11)
    results, errors = [None] * len(loads), []

    def work(k):
        try:
            for i in range(k, len(loads), 4):
                results[i] = moorsolve.solve(with_force(held, loads[i]),
                                             solver=("ipopt", "newton")[i % 2])
        except Exception as err:          # pragma: no cover - reported below
            errors.append(err)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for result in results:
        assert result.converged
        assert_same_answer(results[0], result, 1e-9)


# ---- lazy legs and profiles ----------------------------------------------------------------


def test_lazy_profiles_end_at_the_line_ends_with_the_end_tensions():
    result = moorsolve.solve(with_force(moorsolve.load_case(DOCK), (2e6, 1e6, 0.0)))
    for leg in result.legs:
        prof = leg.profile
        start = np.array([prof["x_m"][0], prof["y_m"][0], prof["z_m"][0]])
        end = np.array([prof["x_m"][-1], prof["y_m"][-1], prof["z_m"][-1]])
        np.testing.assert_allclose(start, leg.anchor, atol=1e-6)
        np.testing.assert_allclose(end, leg.fairlead, atol=1e-6)
        assert prof["tension_N"][-1] == pytest.approx(leg.fairlead_tension_N, rel=1e-9)
        assert prof["tension_N"][0] == pytest.approx(leg.anchor_tension_N, rel=1e-9)
        assert set(leg.to_dict()["profile"]) >= {"x_m", "y_m", "z_m", "tension_N"}


def test_lazy_legs_and_profiles_are_made_once_for_many_threads():
    result = moorsolve.solve(with_force(moorsolve.load_case(DOCK), (3e6, -1e6, 1e7)))
    seen, errors = [], []

    def read():
        try:
            seen.append([(id(leg), leg.profile["z_m"].copy()) for leg in result.legs])
        except Exception as err:          # pragma: no cover - reported below
            errors.append(err)

    threads = [threading.Thread(target=read) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    first = seen[0]
    for other in seen[1:]:
        assert [i for i, _ in other] == [i for i, _ in first]   # the same leg objects
        for (_, a), (_, b) in zip(first, other):
            np.testing.assert_array_equal(a, b)


def test_overload_from_the_end_forces_is_the_overload_of_the_legs():
    case = with_force(moorsolve.load_case(DOCK), (1.1e7, 0.0, 0.0))
    result = moorsolve.solve(case, solver="newton", allow_overload=True)
    problem = get_problem(case)
    with problem.lock:
        post = problem.post(result.state, problem.parameters(case))
    fast = over_mbl(result, problem, post)
    assert fast and fast == over_mbl(result)
    with pytest.raises(moorsolve.ConvergenceError, match="overload: " + fast[0].split(":")[0]):
        moorsolve.solve(case, solver="newton")


# ---- memos never serve a stale answer ---------------------------------------------------------


def test_cases_sharing_lines_get_their_own_answers():
    """Cases made with dataclasses.replace share the lines tuple and the memos keyed by
    it; each must still get the answer of a case loaded from scratch."""
    base = moorsolve.load_case(DOCK)
    for load in random_loads(4, 5e6, 3e7, seed=11):
        shared = with_force(base, load)
        shared_parts.clear()          # a case loaded anew that shares nothing with base
        fresh = with_force(moorsolve.load_case(DOCK), load)
        assert shared.lines is base.lines and fresh.lines is not base.lines
        assert_same_answer(moorsolve.solve(fresh, solver="newton"),
                           moorsolve.solve(shared, solver="newton"), 1e-12)
    again = with_force(base, (1e6, 0.0, 0.0))
    first = moorsolve.solve(again, solver="newton")
    assert_same_answer(first, moorsolve.solve(again, solver="newton"), 0.0)


@pytest.mark.parametrize("path,loads", [
    (DOCK, [(1e6, 2e6, 1e7), (-3e6, 5e5, -2e7)]),
    (SPAR, [(6e5, -2e5, 0, 0, 0, 1e6), (1e6, 3e5, 0, 0, 0, -2e6)])], ids=["dock", "spar"])
def test_a_case_differing_only_in_its_forces_derives_what_a_fresh_case_does(path, loads):
    """A new case that differs from the last one on its lines only in its constant forces
    takes over that case's load-independent values (prepared._sibling): every one must be
    what a case loaded from scratch derives, and the parameter vector its own."""
    base = moorsolve.load_case(path)
    first, second = with_force(base, loads[0]), with_force(base, loads[1])
    shared_parts.clear()              # a case loaded anew that shares nothing with base
    fresh = with_force(moorsolve.load_case(path), loads[1])
    derived = (prepared.line_kinds_of, prepared.structure_key, prepared.geometry_key,
               scales, problem_key)
    for fn in derived:
        fn(first)
    assert prepared._sibling(second) is first and prepared._sibling(fresh) is None
    for fn in derived:
        assert fn(second) == fn(fresh), fn.__name__
    np.testing.assert_array_equal(prepared.load_mask(second), prepared.load_mask(fresh))
    np.testing.assert_array_equal(prepared.case_parameters(second),
                                  prepared.case_parameters(fresh))
    assert not np.array_equal(prepared.case_parameters(second),
                              prepared.case_parameters(first))
    # Anything else that differs (here the body's mass) makes a case derive on its own.
    heavier = dataclasses.replace(second, bodies=(dataclasses.replace(
        second.bodies[0], mass=(second.bodies[0].mass or 1e6) * 1.01),))
    assert prepared._sibling(heavier) is None
    body = get_problem(heavier).layout.slice(f"body[{heavier.bodies[0].name}].mass")
    assert prepared.case_parameters(heavier)[body][0] == heavier.bodies[0].mass


def test_a_long_chain_of_siblings_derives_without_recursion():
    """Cases made one after another are each other's siblings; asking the last for its
    parameters first must not walk the chain back (a RecursionError past ~1000)."""
    base = moorsolve.load_case(DOCK)
    cases = [with_force(base, (1e3 * i, 0.0, 0.0)) for i in range(2500)]
    for case in cases:
        prepared.structure_key(case)
    for i in (2499, 0, 1200):
        assert prepared.case_parameters(cases[i])[6] == pytest.approx(1e3 * i)


def test_rest_state_is_shared_by_loads_and_not_by_geometries():
    base = moorsolve.load_case(DOCK)
    a, b = with_force(base, (1e6, 0.0, 0.0)), with_force(base, (0.0, -3e6, 1e7))
    problem = get_problem(a)
    assert get_problem(b) is problem
    np.testing.assert_array_equal(rest_point(problem, a, 1e-9), rest_point(problem, b, 1e-9))
    legs = list(base.lines)
    legs[0] = dataclasses.replace(legs[0], segments=(dataclasses.replace(
        legs[0].segments[0], length=legs[0].segments[0].length + 2.0),))
    longer = with_force(dataclasses.replace(base, lines=tuple(legs)), (1e6, 0.0, 0.0))
    assert get_problem(longer) is problem
    assert not np.array_equal(rest_point(problem, longer, 1e-9), rest_point(problem, a, 1e-9))
    # ... and its answer is that of the same case loaded from a file.
    data = {**base.source}
    data["legs"] = [dict(leg) for leg in base.source["legs"]]
    data["legs"][0]["segments"] = [dict(data["legs"][0]["segments"][0])]
    data["legs"][0]["segments"][0]["length"] = legs[0].segments[0].length
    fresh = with_force(moorsolve.load_case(data), (1e6, 0.0, 0.0))
    assert_same_answer(moorsolve.solve(fresh, solver="newton"),
                       moorsolve.solve(longer, solver="newton"), 1e-12)


def test_a_tide_is_geometry_not_load():
    """The water level moves the rest state (a floating body rises with it): two cases
    differing in it alone must not share a rest state, as two loads do."""
    base = with_force(moorsolve.load_case(SPAR), (6e5, 0.0, 0.0, 0.0, 0.0, 0.0))
    tide = dataclasses.replace(base, environment=dataclasses.replace(
        base.environment, water_level=2.0))
    problem = get_problem(base)
    assert get_problem(tide) is problem
    assert prepared.geometry_key(base) != prepared.geometry_key(tide)
    assert not np.array_equal(rest_point(problem, base, 1e-9), rest_point(problem, tide, 1e-9))


# ---- the Newton path over the whole yaw range ---------------------------------------------


@pytest.mark.parametrize("moment", [5e6, 1e7])
def test_newton_follows_a_large_turn_without_ipopt(moment):
    """The spar without its yaw spring turns 25 and 52 deg under these couples: the kernel
    follows the load up in steps (no IPOPT fallback) to IPOPT's load-stepped answer."""
    spar = moorsolve.load_case(SPAR)
    body = dataclasses.replace(spar.bodies[0], stiffness=None,
                               loads=BodyLoads(force=(3e5, 0.0, 0.0, 0.0, 0.0, moment)))
    case = dataclasses.replace(spar, bodies=(body,))
    ref = moorsolve.solve(case)
    fast = moorsolve.solve(case, solver="newton")
    assert fast.solver == "newton" and not fast.notes
    assert abs(fast.bodies[0]["yaw_deg"]) > 20
    assert_same_answer(ref, fast, 1e-8)


# ---- the audit, on by default, off on request -----------------------------------------------


def test_audit_false_skips_only_the_audit(monkeypatch):
    """``audit=False`` returns the audited answer without running the audit; the warnings
    (here a hose floating on the surface) are there either way."""
    from moorsolve.solve import equilibrium

    hose = moorsolve.load_case({
        "environment": {"depth": 50},
        "line_types": {"hose": {"weight_in_water": -100.0, "ea": 1e8}},
        "legs": [{"name": "H1", "anchor": [0, 0], "fairlead": [100, 0, 0],
                  "segments": [{"type": "hose", "length": 120}]}]})
    dock = with_force(moorsolve.load_case(DOCK), (2e6, -1e6, 5e6))
    audited = {name: moorsolve.solve(case, solver="newton")
               for name, case in (("hose", hose), ("dock", dock))}
    assert [w["code"] for w in audited["hose"].warnings] == ["floating"]

    def refuse(*args, **kwargs):
        raise AssertionError("the audit ran")

    monkeypatch.setattr(equilibrium, "audit_result", refuse)
    with pytest.raises(AssertionError, match="the audit ran"):
        moorsolve.solve(dock, solver="newton")
    for name, case in (("hose", hose), ("dock", dock)):
        fast = moorsolve.solve(case, solver="newton", audit=False)
        assert fast.warnings == audited[name].warnings
        assert_same_answer(audited[name], fast, 0.0)
