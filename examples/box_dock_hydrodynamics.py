"""Long-wave hydrodynamics of a floating box (a dock or a barge) in finite depth, as a case-file
table: the coefficients of ``cases/dock_sea.yaml`` for surge, sway and yaw, from closed
forms and sums an engineer can check by hand (a first estimate, not a BEM solution):

- added mass: strip theory with a flat plate's ``rho pi T^2 / 2`` per metre (a plate of
  height 2T in infinite fluid, ``rho pi (2T)^2 / 4``, halved by the free surface;
  DNV-RP-C205 (2010) Table D-1), along the length for sway, along the beam for surge, and
  ``int x^2`` of the sway strips for yaw; constant in frequency, no shallow-water increase;
- excitation: the Froude-Krylov force and yaw moment of the incident wave's finite-depth
  pressure ``rho g a cosh k(z + h) / cosh kh`` summed over the box's walls (panels of at
  most a tenth of the shortest wave), scaled by ``1 + A / (rho V)`` of each DOF for the
  diffraction (the long-wave Morison/G.I. Taylor form), phase ``Re{F e^{+i omega t}}`` for
  a crest at the origin at t = 0, wave heading relative to the box's x axis;
- radiation damping from the excitation by the Haskind relation,
  ``B_ij = k / (16 pi rho g c_g) int_0^2pi X_i X_j^* d beta`` (Newman, "Marine
  Hydrodynamics", 1977, section 6.18; in deep water ``omega^3 / (8 pi rho g^3) int``);
- mean drift: each wall facing the waves reflects ``R^2 = 1 - T_r^2`` of the energy, with
  Wiegel's (1960) power transmission under a barrier of draft T,
  ``T_r^2 = (2k(h - T) + sinh 2k(h - T)) / (2kh + sinh 2kh)``, and takes Maruo's (1960)
  reflection force ``0.5 rho g a^2 R^2 cos^2(theta)`` per metre of wall, normal to it
  (theta the angle between the waves and the wall's normal); no yaw drift moment.

Run: ``python examples/box_dock_hydrodynamics.py`` prints the YAML block.
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from moorsolve.dynamics.hydro import table_mapping

RHO, G = 1025.0, 9.80665


def wavenumber(omega, depth: float) -> np.ndarray:
    """Finite-depth wave number: ``omega^2 = g k tanh(k h)`` by Newton's method [1/m]."""
    w = np.asarray(omega, dtype=float)
    k = np.maximum(w ** 2 / G, w / math.sqrt(G * depth))
    for _ in range(50):
        f = G * k * np.tanh(k * depth) - w ** 2
        df = G * np.tanh(k * depth) + G * k * depth / np.cosh(k * depth) ** 2
        k = k - f / df
    return k


def _walls(length: float, beam: float, draft: float, panel: float):
    """Panels of the four walls: centres (n, 3), outward normals (n, 3), areas (n,)."""
    out = []
    nz = max(int(math.ceil(draft / panel)), 4)
    z = -draft + (np.arange(nz) + 0.5) * draft / nz
    for normal, span, fixed in (((1, 0), beam, length / 2), ((-1, 0), beam, length / 2),
                                ((0, 1), length, beam / 2), ((0, -1), length, beam / 2)):
        ns = max(int(math.ceil(span / panel)), 4)
        s = -span / 2 + (np.arange(ns) + 0.5) * span / ns
        S, Z = np.meshgrid(s, z, indexing="ij")
        if normal[0]:
            x, y = np.full(S.size, normal[0] * fixed), S.ravel()
        else:
            x, y = S.ravel(), np.full(S.size, normal[1] * fixed)
        n = np.tile([normal[0], normal[1], 0.0], (S.size, 1))
        out.append((np.column_stack([x, y, Z.ravel()]), n,
                    np.full(S.size, span / ns * draft / nz)))
    return tuple(np.concatenate(parts) for parts in zip(*out))


def box_table(length: float, beam: float, draft: float, depth: float, omega,
              headings_deg) -> dict:
    """The table (SI, body frame, origin at the waterline at the box's centre)."""
    w = np.asarray(omega, dtype=float)
    k = wavenumber(w, depth)
    cg = 0.5 * w / k * (1 + 2 * k * depth / np.sinh(2 * k * depth))
    strip = RHO * math.pi * draft ** 2 / 2
    volume = length * beam * draft
    A = np.zeros((w.size, 6, 6))
    A[:, 0, 0] = strip * beam
    A[:, 1, 1] = strip * length
    A[:, 5, 5] = strip * length ** 3 / 12
    inertia_fluid = RHO * volume * (length ** 2 + beam ** 2) / 12
    scale = np.array([1 + A[0, 0, 0] / (RHO * volume), 1 + A[0, 1, 1] / (RHO * volume),
                      1 + A[0, 5, 5] / inertia_fluid])
    panel = min(0.1 * 2 * math.pi / k.max(), draft / 4)
    centre, normal, area = _walls(length, beam, draft, panel)
    lever = centre[:, 0] * normal[:, 1] - centre[:, 1] * normal[:, 0]      # (r x n)_z

    def force(beta):
        c, s = math.cos(beta), math.sin(beta)
        phase = np.exp(-1j * np.outer(k, centre[:, 0] * c + centre[:, 1] * s))
        decay = np.cosh(np.outer(k, centre[:, 2] + depth)) / np.cosh(k * depth)[:, None]
        p = RHO * G * phase * decay * area                  # (n_omega, n_panels)
        X = np.zeros((w.size, 6), dtype=complex)
        X[:, 0] = -(p @ normal[:, 0]) * scale[0]
        X[:, 1] = -(p @ normal[:, 1]) * scale[1]
        X[:, 5] = -(p @ lever) * scale[2]
        return X

    betas = np.linspace(0, 2 * math.pi, 361)[:-1]
    acc = sum(np.einsum("wi,wj->wij", force(b), np.conj(force(b))) for b in betas)
    B = np.real(acc * (2 * math.pi / betas.size)) * (k / (16 * math.pi * RHO * G * cg))[
        :, None, None]
    gap = depth - draft
    transmitted = (2 * k * gap + np.sinh(2 * k * gap)) / (2 * k * depth + np.sinh(2 * k * depth))
    reflected = 1.0 - transmitted
    exc, mean = {}, {}
    for h in headings_deg:
        beta = math.radians(h)
        X = force(beta)
        exc[float(h)] = X
        d = np.array([math.cos(beta), math.sin(beta)])
        D = np.zeros((w.size, 6))
        for n, width in (((1, 0), beam), ((-1, 0), beam), ((0, 1), length), ((0, -1), length)):
            facing = -(n[0] * d[0] + n[1] * d[1])           # cos(theta) > 0: waves hit it
            if facing > 0:
                D[:, 0] -= n[0] * 0.5 * RHO * G * reflected * facing ** 2 * width
                D[:, 1] -= n[1] * 0.5 * RHO * G * reflected * facing ** 2 * width
        mean[float(h)] = D
    return table_mapping(w, A, B, exc, mean)


def main(argv=None) -> None:
    import yaml
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--length", type=float, default=246.4)
    p.add_argument("--beam", type=float, default=51.0)
    p.add_argument("--draft", type=float, default=5.0)
    p.add_argument("--depth", type=float, default=20.85)
    args = p.parse_args(argv)
    table = box_table(args.length, args.beam, args.draft, args.depth,
                      np.linspace(0.2, 3.2, 31), np.arange(0.0, 360.0, 30.0))
    print(yaml.safe_dump({"hydrodynamics": table}, default_flow_style=None, width=100,
                         sort_keys=False))


if __name__ == "__main__":
    main()
