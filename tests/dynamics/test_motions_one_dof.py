"""A one-DOF moored body in a sea state against closed forms computed independently here
(scipy quad at fine tolerance, a direct double sum for the slow drift)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

import moorsolve
from moorsolve.dynamics.motions import motions
from moorsolve.dynamics.spectra import jonswap
from moorsolve.studies.stiffness import coupled_stiffness

HS, TP, GAMMA = 3.0, 8.0, 2.0
MASS, ADDED, RAD_DAMPING = 1.0e6, 5.0e5, 4.0e4
ZETA = 0.08
OMEGA = np.linspace(0.2, 3.0, 57)


# The tables (at OMEGA) and, between their points, the linear interpolation moorsolve
# documents: the reference below integrates that same piecewise-linear model.
X_TABLE = 3e5 * np.exp(-0.8 * OMEGA) + 1j * 5e4 * OMEGA
D_TABLE = 4e3 * OMEGA ** 2 / (1 + OMEGA ** 2)
A_TABLE = ADDED * (1 + 0.2 * np.sin(OMEGA))
B_TABLE = RAD_DAMPING * OMEGA * np.exp(-OMEGA)


def force(w):
    return np.interp(w, OMEGA, X_TABLE.real) + 1j * np.interp(w, OMEGA, X_TABLE.imag)


def drift(w):
    return np.interp(w, OMEGA, D_TABLE)


def added(w):
    return np.interp(w, OMEGA, A_TABLE)


def damping(w):
    return np.interp(w, OMEGA, B_TABLE)


def one_dof_case(drift_table: bool = True) -> dict:
    n = OMEGA.size
    A = np.zeros((n, 6, 6))
    B = np.zeros((n, 6, 6))
    A[:, 0, 0] = A_TABLE
    B[:, 0, 0] = B_TABLE
    X = np.zeros((n, 6), dtype=complex)
    X[:, 0] = X_TABLE
    D = np.zeros((n, 6))
    D[:, 0] = D_TABLE
    hydro = {"source": "table", "omega": OMEGA.tolist(), "added_mass": A.tolist(),
             "damping": B.tolist(),
             "excitation": [{"heading_deg": 0, "re": X.real.tolist(), "im": X.imag.tolist()}]}
    if drift_table:
        hydro["mean_drift"] = [{"heading_deg": 0, "values": D.tolist()}]
    return {"environment": {"depth": 50, "waves": {"hs": HS, "tp": TP, "toward_deg": 0,
                                                   "spectrum": {"model": "jonswap",
                                                                "gamma": GAMMA}}},
            "line_types": {"h": {"weight_in_water": 0, "ea": 1e6}},
            "bodies": [{"name": "b", "free": ["surge"], "mass": MASS, "hydrodynamics": hydro,
                        "damping": {"critical_fraction": {"surge": ZETA}}}],
            "lines": [{"name": n, "from": [x, 0, 0], "to": {"body": "b", "at": [0, 0, 0]},
                       "segments": [{"type": "h", "length": 99}]}
                      for n, x in (("w", -100), ("e", 100))]}


@pytest.fixture(scope="module")
def solved():
    case = moorsolve.load_case(one_dof_case())
    m = motions(case, n_omega=2000)
    K = coupled_stiffness(m.result)[0][0, 0]
    return m, K


def S(w):
    return float(jonswap(w, HS, TP, GAMMA))


def test_wave_frequency_closed_form(solved):
    m, K = solved
    lo, hi = OMEGA[0], OMEGA[-1]
    b_ext = 2 * ZETA * math.sqrt(K * (MASS + added(lo)))

    def H2(w):
        z = -w ** 2 * (MASS + added(w)) + 1j * w * (damping(w) + b_ext) + K
        return abs(force(w) / z) ** 2

    pts = OMEGA[1:-1]
    m0 = quad(lambda w: H2(w) * S(w), lo, hi, limit=500, epsabs=0, epsrel=1e-10,
              points=pts)[0]
    m2 = quad(lambda w: w ** 2 * H2(w) * S(w), lo, hi, limit=500, epsabs=0, epsrel=1e-10,
              points=pts)[0]
    body = m.body("b")
    sigma, tz = math.sqrt(m0), 2 * math.pi * math.sqrt(m0 / m2)
    # The band kept drops 1e-6 of the spectrum's energy on each side; 2000 points.
    assert body.wf["sigma"][0] == pytest.approx(sigma, rel=1e-4)
    assert body.wf["tz_s"][0] == pytest.approx(tz, rel=1e-4)
    assert body.wf["significant"][0] == pytest.approx(2 * sigma, rel=1e-4)
    assert body.wf["max"][0] == pytest.approx(sigma * math.sqrt(2 * math.log(3 * 3600 / tz)),
                                              rel=1e-4)


def test_mean_drift_closed_form(solved):
    m, K = solved
    F = 2 * quad(lambda w: drift(w) * S(w), OMEGA[0], OMEGA[-1], epsrel=1e-10,
                 points=OMEGA[1:-1], limit=500)[0]
    assert m.body("b").mean_drift[0] == pytest.approx(F, rel=1e-5)
    # The static re-solve carries it: the mean offset is the line's answer to F, to the
    # line's own non-linearity (checked against the linear stiffness to 1 %).
    assert m.body("b").mean[0] == pytest.approx(F / K, rel=1e-2)
    assert m.result.certificate.certified
    assert m.result.loads  # the drift force is a constant force of the re-solve


def test_slow_drift_against_double_sum(solved):
    m, K = solved
    # Independent: the slow-drift force of a discrete sea (component amplitudes
    # a_i^2 = 2 S(w_i) dw) has difference-frequency lines at w_j - w_i of variance
    # 2 (a_i a_j D_ij)^2 with Newman's D_ij = D((w_i + w_j)/2); the response of each is
    # |H(w_j - w_i)|^2 times it, with A at the lowest frequency and the extra damping.
    lo, hi = m.omega[0], m.omega[-1]
    M0 = MASS + added(OMEGA[0])
    b_ext = 2 * ZETA * math.sqrt(K * M0)
    w = np.linspace(lo, hi, 3001)
    dw = w[1] - w[0]
    a2 = 2 * jonswap(w, HS, TP, GAMMA) * dw
    i, j = np.triu_indices(w.size, 1)
    mu = w[j] - w[i]
    keep = mu <= m.sea["slow_drift_below_rad_s"]   # the slow band: below the waves' energy
    i, j, mu = i[keep], j[keep], mu[keep]
    Dij = drift(0.5 * (w[i] + w[j]))
    var_f = 2 * a2[i] * a2[j] * Dij ** 2
    H2 = 1 / np.abs(-mu ** 2 * M0 + 1j * mu * b_ext + K) ** 2
    sigma = math.sqrt(np.sum(var_f * H2))
    sigma2 = math.sqrt(np.sum(var_f * H2 * mu ** 2))
    lf = m.body("b").lf
    assert lf["sigma"][0] == pytest.approx(sigma, rel=5e-3)
    assert lf["tz_s"][0] == pytest.approx(2 * math.pi * sigma / sigma2, rel=1e-2)


def test_design_offset(solved):
    m, _ = solved
    b = m.body("b")
    mean = abs(b.mean[0])
    expected = max(mean + b.lf["significant"][0] + b.wf["max"][0],
                   mean + b.lf["max"][0] + b.wf["significant"][0])
    assert b.design_offset_m == pytest.approx(expected, rel=1e-9)
    assert b.design_offset_m > mean


def test_rao_and_json(solved):
    m, K = solved
    w = m.omega[10]
    b_ext = 2 * ZETA * math.sqrt(K * (MASS + added(OMEGA[0])))
    x = force(w) / (-w ** 2 * (MASS + added(w)) + 1j * w * (damping(w) + b_ext) + K)
    assert m.body("b").rao[10, 0] == pytest.approx(x, rel=1e-9)
    d = m.to_dict()
    assert set(d["motions"]["bodies"][0]) >= {"name", "dofs", "mean", "wf", "lf",
                                              "design_offset_m"}
    assert len(d["motions"]["rao"]["b"]["re"]) == len(d["motions"]["omega"])
    assert d["sea"]["simulated"] == ["mean_drift", "wave_frequency", "slow_drift"]


def test_without_drift_tables_no_slow_drift():
    m = motions(moorsolve.load_case(one_dof_case(drift_table=False)))
    assert m.sea["simulated"] == ["wave_frequency"]
    assert m.body("b").lf["sigma"][0] == 0.0
    assert m.body("b").mean_drift[0] == 0.0
