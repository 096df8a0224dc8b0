"""Long-wave hydrodynamics of a floating vertical cylinder, written as a case-file table.

The coefficients of ``cases/buoy_sea.yaml``, from closed forms an engineer can check by
hand (deep water, ``k = omega^2 / g``; a first estimate, not a BEM solution):

- added mass: surge and sway from strip theory, ``rho pi a^2`` per metre of draft (a
  circular section's added-mass coefficient 1; DNV-RP-C205 Table D-1), integrated over the
  draft for the roll/pitch terms about the waterline; heave from a circular disc's
  ``8/3 rho a^3`` (DNV-RP-C205 Table D-2) halved for one face;
- excitation: Morison inertia (Froude-Krylov plus added mass, ``(1 + Ca) rho pi a^2``) of
  the deep-water particle acceleration ``i omega^2 e^{kz}`` over the draft, and the
  Froude-Krylov pressure on the bottom less the heave added mass's share for heave, all
  with phase ``Re{F e^{+i omega t}}`` for a wave crest at the origin at t = 0;
- radiation damping from the excitation by the Haskind relation in deep water (Newman,
  "Marine Hydrodynamics", 1977, section 6.18):
  ``B_ij = omega^3 / (8 pi rho g^3) int_0^2pi X_i X_j^* d beta``;
- mean drift (illustrative): ``2/3 rho g a`` (the short-wave limit of a vertical cylinder,
  Havelock 1940) blended in by ``(ka)^4 / (1 + (ka)^4)``.

Run: ``python examples/cylinder_buoy_hydrodynamics.py`` prints the YAML block.
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from moorsolve.dynamics.hydro import table_mapping

RHO, G = 1025.0, 9.80665


def cylinder_table(radius: float, draft: float, omega, headings_deg) -> dict:
    """The table (SI, body frame, origin at the waterline on the axis)."""
    a, T = radius, draft
    w = np.asarray(omega, dtype=float)
    k = w ** 2 / G
    strip = RHO * math.pi * a ** 2
    A = np.zeros((w.size, 6, 6))
    A[:, 0, 0] = A[:, 1, 1] = strip * T
    A[:, 2, 2] = 4.0 / 3.0 * RHO * a ** 3
    A[:, 3, 3] = A[:, 4, 4] = strip * T ** 3 / 3
    A[:, 0, 4] = A[:, 4, 0] = -strip * T ** 2 / 2      # x = z theta, z < 0
    A[:, 1, 3] = A[:, 3, 1] = strip * T ** 2 / 2       # y = -z phi
    decay = np.exp(-k * T)
    f1 = 1j * 2 * strip * w ** 2 * (1 - decay) / k            # along the waves
    m1 = 1j * 2 * strip * w ** 2 * (-1 / k ** 2 + decay * (T / k + 1 / k ** 2))
    f3 = (RHO * G * math.pi * a ** 2 - w ** 2 * A[:, 2, 2]) * decay

    def force(beta):
        c, s = math.cos(beta), math.sin(beta)
        X = np.zeros((w.size, 6), dtype=complex)
        X[:, 0], X[:, 1], X[:, 2] = c * f1, s * f1, f3
        X[:, 3], X[:, 4] = -s * m1, c * m1
        return X

    # Haskind: the integral over headings of X_i X_j^*, by a fine sum round the compass.
    betas = np.linspace(0, 2 * math.pi, 721)[:-1]
    acc = sum(np.einsum("wi,wj->wij", force(b), np.conj(force(b))) for b in betas)
    B = np.real(acc * (2 * math.pi / betas.size)) * (w ** 3 / (8 * math.pi * RHO * G ** 3))[
        :, None, None]
    ka4 = (k * a) ** 4
    drift = 2.0 / 3.0 * RHO * G * a * ka4 / (1 + ka4)
    exc, mean = {}, {}
    for h in headings_deg:
        X = force(math.radians(h))
        exc[float(h)] = X
        D = np.zeros((w.size, 6))
        D[:, 0] = math.cos(math.radians(h)) * drift
        D[:, 1] = math.sin(math.radians(h)) * drift
        mean[float(h)] = D
    return table_mapping(w, A, B, exc, mean)


def main(argv=None) -> None:
    import yaml

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--radius", type=float, default=2.0)
    p.add_argument("--draft", type=float, default=6.0)
    args = p.parse_args(argv)
    table = cylinder_table(args.radius, args.draft, np.linspace(0.2, 3.0, 29),
                           np.arange(0.0, 360.0, 30.0))
    print(yaml.safe_dump({"hydrodynamics": table}, default_flow_style=None, width=100,
                         sort_keys=False))


if __name__ == "__main__":
    main()
