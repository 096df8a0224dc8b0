"""Three platforms on shared lines, every body free in six DOFs with its own table
hydrodynamics, one turned by 20 deg: the coupled motions against an independent
frequency-domain computation written here in plain numpy and scipy (the module's solver
is not called; the stiffness is the equilibrium's own, an input of both)."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
import yaml
from scipy.spatial.transform import Rotation

import moorsolve
from moorsolve.dynamics.motions import motions
from moorsolve.dynamics.spectra import jonswap
from moorsolve.studies.stiffness import coupled_stiffness

HS, TP, TOWARD = 4.0, 10.0, 15.0
OMEGA = np.linspace(0.15, 2.5, 48)
HEADINGS = np.arange(0.0, 360.0, 30.0)
INERTIA = [8.0e8, 8.0e8, 1.2e9]
LINEAR = [4e5, 4e5, 2e6, 5e8, 5e8, 6e8]
SCALE = np.array([1.0, 1.0, 1.0, 20.0, 20.0, 20.0])       # rotations' lever [m]


def spd(rng, size, n):
    out = []
    L = rng.normal(size=(6, 6)) * 0.3 + np.eye(6)
    base = L @ L.T
    for k in range(n):
        out.append((base * (1 + 0.3 * math.sin(k / 7))) * size * np.outer(SCALE, SCALE))
    return np.array(out)


def hydro(seed):
    rng = np.random.default_rng(seed)
    n = OMEGA.size
    A = spd(rng, 1.5e6, n)
    B = spd(rng, 2e5, n) * (OMEGA * np.exp(-OMEGA))[:, None, None]
    exc, drift = [], []
    for h in HEADINGS:
        c, s = math.cos(math.radians(h)), math.sin(math.radians(h))
        amp = 2e6 * np.exp(-0.5 * OMEGA)[:, None] * np.array([c, s, 1.5, 8 * s, 8 * c, 3 * s * c])
        phase = np.exp(1j * (OMEGA[:, None] * rng.normal(size=6) + rng.normal(size=6)))
        X = amp * SCALE * phase
        exc.append({"heading_deg": float(h), "re": X.real.tolist(), "im": X.imag.tolist()})
        D = 3e4 * (OMEGA ** 2 / (1 + OMEGA ** 2))[:, None] * np.array([c, s, 0.1, 0.0, 0.0,
                                                                         5 * s * c])
        drift.append({"heading_deg": float(h), "values": D.tolist()})
    return {"source": "table", "omega": OMEGA.tolist(), "added_mass": A.tolist(),
            "damping": B.tolist(), "excitation": exc, "mean_drift": drift}


@pytest.fixture(scope="module")
def scene(cases_dir):
    data = yaml.safe_load((cases_dir / "three_platforms.yaml").read_text())
    data["environment"]["waves"] = {"hs": HS, "tp": TP, "toward_deg": TOWARD,
                                    "spectrum": {"model": "jonswap", "gamma": 3.3}}
    for k, body in enumerate(data["bodies"]):
        body["inertia"] = INERTIA
        body["hydrodynamics"] = hydro(k)
        body["damping"] = {"linear": LINEAR}
    # The middle platform turned by 20 deg, its fairleads turned with it (same places).
    data["bodies"][1]["orientation_deg"] = [0.0, 0.0, 20.0]
    turn = Rotation.from_euler("z", -20.0, degrees=True)
    for line in data["lines"]:
        for end in ("from", "to"):
            e = line[end]
            if isinstance(e, dict) and e.get("body") == "middle":
                e["at"] = turn.apply(e["at"]).tolist()
    case = moorsolve.load_case(data)
    m = motions(case, n_omega=1500)
    return case, m


def rigid_mass(mass, cg, inertia):
    m = np.zeros((6, 6))
    m[:3, :3] = mass * np.eye(3)
    cx, cy, cz = cg
    c = np.array([[0, -cz, cy], [cz, 0, -cx], [-cy, cx, 0]])
    m[:3, 3:] = -mass * c
    m[3:, :3] = mass * c
    m[3:, 3:] = np.diag(inertia) - mass * c @ c
    return m


def velocity_map(roll, pitch, yaw):
    """Body-frame velocity from the rates of (x, y, z, roll, pitch, yaw)."""
    R = Rotation.from_euler("ZYX", [yaw, pitch, roll]).as_matrix()
    axes = np.column_stack([Rotation.from_euler("ZY", [yaw, pitch]).apply([1, 0, 0]),
                            Rotation.from_euler("Z", yaw).apply([0, 1, 0]), [0, 0, 1]])
    J = np.zeros((6, 6))
    J[:3, :3] = R.T
    J[3:, 3:] = R.T @ axes
    return J


def interp_entries(table, w):
    table = np.asarray(table)
    flat = table.reshape(table.shape[0], -1)
    return np.stack([np.interp(w, OMEGA, flat[:, k]) for k in range(flat.shape[1])],
                    axis=-1).reshape((w.size,) + table.shape[1:])


def at_heading(tables, beta, key):
    b = beta % 360.0
    k = int(b // 30.0)
    t = (b - 30.0 * k) / 30.0
    lo, hi = tables[k % 12], tables[(k + 1) % 12]
    if key == "values":
        return (1 - t) * np.asarray(lo["values"]) + t * np.asarray(hi["values"])
    X = lambda e: np.asarray(e["re"]) + 1j * np.asarray(e["im"])  # noqa: E731
    return (1 - t) * X(lo) + t * X(hi)


def reference(case, m):
    K, labels = coupled_stiffness(m.result)
    n = len(labels)
    w = np.linspace(m.omega[0], m.omega[-1], 6001)
    Mw = np.zeros((w.size, n, n), dtype=complex)
    Bw = np.zeros((w.size, n, n))
    M0 = np.zeros((n, n))
    Bx = np.zeros((n, n))
    F = np.zeros((w.size, n), dtype=complex)
    Dq = []
    for k, body in enumerate(case.bodies):
        rb = m.result.body_named(body.name)
        roll, pitch, yaw = (math.radians(rb[f"{a}_deg"]) for a in ("roll", "pitch", "yaw"))
        J = velocity_map(roll, pitch, yaw)
        s = slice(6 * k, 6 * k + 6)
        assert labels[6 * k] == f"{body.name}.surge"
        raw = hydro(k)
        Mb = rigid_mass(body.mass, body.centre_of_gravity, INERTIA)
        Mw[:, s, s] = J.T @ (Mb + interp_entries(raw["added_mass"], w)) @ J
        Bw[:, s, s] = J.T @ interp_entries(raw["damping"], w) @ J
        M0[s, s] = J.T @ (Mb + np.asarray(raw["added_mass"][0])) @ J
        Bx[s, s] = J.T @ np.diag(LINEAR) @ J
        beta = TOWARD - math.degrees(yaw)
        F[:, s] = interp_entries(at_heading(raw["excitation"], beta, "x"), w) @ J
        Dq.append((s, at_heading(raw["mean_drift"], beta, "values") @ J))
    Z = -w[:, None, None] ** 2 * Mw + 1j * w[:, None, None] * (Bw + Bx) + K
    X = np.linalg.solve(Z, F[:, :, None])[:, :, 0]
    S = jonswap(w, HS, TP, 3.3)
    sigma_wf = np.sqrt(np.trapezoid(np.abs(X) ** 2 * S[:, None], w, axis=0))
    # Slow drift: Newman's cross-spectra by an explicit sum over wave pairs on the grid.
    D = np.zeros((OMEGA.size, n))
    for s, d in Dq:
        D[:, s] = d
    Dw = interp_entries(D, w)
    dw = w[1] - w[0]
    mu_max = m.sea["slow_drift_below_rad_s"]
    kmax = int(mu_max / dw)
    lf_var = np.zeros(n)
    mus, SF = [], []
    for j in range(0, kmax + 1, 10):
        a, b = S[: w.size - j], S[j:]
        centre = 0.5 * (w[: w.size - j] + w[j:])
        mid = np.column_stack([np.interp(centre, w, Dw[:, c]) for c in range(n)])
        g = (a * b)[:, None] * mid
        SF.append(8 * np.trapezoid(g[:, :, None] * mid[:, None, :], dx=dw, axis=0))
        mus.append(j * dw)
    mus, SF = np.array(mus), np.array(SF)
    fine = np.linspace(0, mus[-1], 40001)
    SFf = np.stack([np.stack([np.interp(fine, mus, SF[:, r, c]) for c in range(n)], -1)
                    for r in range(n)], 1)
    H = np.linalg.inv(-fine[:, None, None] ** 2 * M0 + 1j * fine[:, None, None] * Bx + K)
    resp = np.real(np.einsum("mij,mjk,mik->mi", H, SFf, np.conj(H)))
    lf_var = np.trapezoid(resp, fine, axis=0)
    mean_drift = {case.bodies[k].name: 2 * np.trapezoid(interp_entries(d, w) * S[:, None],
                                                        w, axis=0)
                  for k, (s, d) in enumerate(Dq)}
    return labels, sigma_wf, np.sqrt(lf_var), mean_drift


def test_coupled_against_numpy(scene):
    case, m = scene
    labels, sigma_wf, sigma_lf, drift = reference(case, m)
    got_wf = np.concatenate([b.wf["sigma"] * np.where(np.arange(6) >= 3, math.radians(1), 1)
                             for b in m.bodies])
    got_lf = np.concatenate([b.lf["sigma"] * np.where(np.arange(6) >= 3, math.radians(1), 1)
                             for b in m.bodies])
    # Within 0.5 % (each DOF that moves at all: above 1e-6 of the largest).
    big = sigma_wf > 1e-6 * sigma_wf.max()
    assert np.allclose(got_wf[big], sigma_wf[big], rtol=5e-3), (got_wf / sigma_wf)
    big = sigma_lf > 1e-3 * sigma_lf.max()
    assert big.sum() >= 6
    assert np.allclose(got_lf[big], sigma_lf[big], rtol=1e-2), (got_lf / sigma_lf)
    for b in m.bodies:
        rb = m.result.body_named(b.name)
        yaw = math.radians(rb["yaw_deg"])
        Rz = Rotation.from_euler("ZYX", [yaw, math.radians(rb["pitch_deg"]),
                                         math.radians(rb["roll_deg"])]).as_matrix()
        # The body-frame generalised drift back to body-frame force: J^-T; global = R.
        J = velocity_map(math.radians(rb["roll_deg"]), math.radians(rb["pitch_deg"]), yaw)
        body_frame = np.linalg.solve(J.T, drift[b.name])
        assert np.allclose(b.mean_drift[:3], Rz @ body_frame[:3], rtol=1e-3,
                           atol=1e-6 * np.abs(body_frame).max())


def test_turned_body_sees_its_own_heading(scene):
    case, m = scene
    middle = m.body("middle")
    assert middle.heading_deg == pytest.approx(TOWARD - m.result.body_named("middle")["yaw_deg"])
    assert m.body("west").heading_deg == pytest.approx(
        TOWARD - m.result.body_named("west")["yaw_deg"])
    assert abs(middle.heading_deg - m.body("west").heading_deg) > 15


def test_design_offset_along_the_mean(scene):
    _, m = scene
    for b in m.bodies:
        rb = m.result.body_named(b.name)
        mean = math.hypot(rb["offset"]["x_m"], rb["offset"]["y_m"])
        assert b.design_offset_m > mean
        horizontal = math.hypot(b.wf["max"][0], b.wf["max"][1]) + math.hypot(
            b.lf["max"][0], b.lf["max"][1])
        assert b.design_offset_m <= mean + 2 * horizontal
