"""One line in many sea states at once (moorsolve.dynamics.line_batch) against the
banded solve of moorsolve.dynamics.line_dynamics, sea state by sea state."""

import numpy as np
import pytest

import moorsolve
from moorsolve.dynamics.line_batch import spectral_tensions
from moorsolve.dynamics.line_dynamics import line_response
from moorsolve.dynamics.line_model import line_model
from moorsolve.dynamics.spectra import jonswap


@pytest.fixture(scope="module")
def buoy_line(cases_dir):
    case = moorsolve.load_case(cases_dir / "buoy_fatigue.yaml")
    result = moorsolve.solve(case)
    return line_model(case, result, "L1", n_elements=30)


@pytest.mark.parametrize("moving_anchor", [False, True])
def test_batch_equals_the_banded_solve_per_sea_state(buoy_line, moving_anchor):
    w = np.linspace(0.3, 2.5, 40)
    rng = np.random.default_rng(5)
    states = [(0.5, 4.5), (2.0, 7.0), (4.0, 10.0), (1.0, 5.0)]
    S = np.array([jonswap(w, hs, tp) for hs, tp in states])
    drive = np.array([(rng.normal(size=(3, 1)) + 1j * rng.normal(size=(3, 1)))
                      * np.exp(-0.3 * w) for _ in states])
    anchor = 0.1 * drive[:, ::-1] if moving_anchor else None
    t_a, t_b, _ = spectral_tensions(buoy_line, w, drive, S, motion_a=anchor, tolerance=1e-8)
    for k in range(len(states)):
        ref = line_response(buoy_line, w, drive[k], linearisation="spectral", spectrum=S[k],
                            motion_a=None if anchor is None else anchor[k], tolerance=1e-8)
        scale = np.max(np.abs(ref.tension_b))
        assert np.max(np.abs(t_b[k] - ref.tension_b)) < 1e-6 * scale
        assert np.max(np.abs(t_a[k] - ref.tension_a)) < 1e-6 * np.max(np.abs(ref.tension_a))
