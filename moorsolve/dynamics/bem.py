"""A body's hydrodynamics computed with Capytaine (BEM), cached on disk.

The optional extra ``moorsolve[hydro]`` (Capytaine: M. Ancellin and F. Dias, "Capytaine:
a Python-based linear potential flow solver", JOSS 4(36), 1341, 2019). The mesh is built
from the body's ``hull`` members (vertical cylinders and boxes, body frame) at its
equilibrium draft, cut at the still water; the radiation and diffraction problems are
solved for the six rigid-body DOFs about the body origin, at the case's water depth,
density and gravity. Capytaine's time dependence is ``e^{-i omega t}``: its exciting force
(Froude-Krylov plus diffraction) is conjugated to the tables' ``e^{+i omega t}``. Capytaine
gives no mean drift here, so a Capytaine body has no slow drift or mean drift force.

Results are cached in a folder (``cache`` in the case, else ``$XDG_CACHE_HOME/moorsolve``
or ``~/.cache/moorsolve``) under a hash of the mesh, frequencies, headings, depth, density,
gravity and Capytaine's version; a lock makes one thread compute a given key at a time.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import threading
from pathlib import Path

import numpy as np

from ..errors import CaseError
from ..model.sea import ExcitationTable, Hydrodynamics

_LOCK = threading.Lock()
DOF_NAMES = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


def _capytaine(path: str):
    try:
        import capytaine
    except ImportError:
        raise CaseError(f"{path}.source", "source capytaine needs the optional extra: pip "
                                          "install 'moorsolve[hydro]' (Capytaine), or give "
                                          "the coefficients as a table or WAMIT files") \
            from None
    return capytaine


def cache_folder(spec) -> Path:
    if spec.cache:
        return Path(spec.cache).expanduser()
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "moorsolve" / "hydro"


def hull_mesh(cpt, body, z_origin: float, panel_size=None):
    """The hull members' mesh (body frame, raised by ``z_origin`` [m], the body origin's
    height above still water), cut at the still water."""
    members = body.hull
    if panel_size is None:
        dims = [d for m in members for d in (m.radius, m.length, m.width, m.top - m.bottom)
                if d > 0]
        panel_size = min(dims) / 6.0
    h = float(panel_size)
    meshes = []
    for m in members:
        height = m.top - m.bottom
        centre = (m.centre[0], m.centre[1], 0.5 * (m.top + m.bottom) + z_origin)
        if m.shape == "cylinder":
            meshes.append(cpt.mesh_vertical_cylinder(
                length=height, radius=m.radius, center=centre,
                resolution=(max(2, math.ceil(m.radius / h)),
                            max(12, math.ceil(2 * math.pi * m.radius / h)),
                            max(2, math.ceil(height / h)))))
        else:
            meshes.append(cpt.mesh_parallelepiped(
                size=(m.length, m.width, height), center=centre,
                resolution=(max(2, math.ceil(m.length / h)), max(2, math.ceil(m.width / h)),
                            max(2, math.ceil(height / h)))))
    mesh = meshes[0]
    for other in meshes[1:]:
        mesh = mesh + other
    return mesh.immersed_part()


def _key(mesh, spec, depth, rho, g, version) -> str:
    digest = hashlib.sha256()
    digest.update(np.ascontiguousarray(mesh.vertices, dtype=float).tobytes())
    digest.update(np.ascontiguousarray(mesh.faces, dtype=np.int64).tobytes())
    digest.update(json.dumps([list(spec.omega), list(spec.headings_deg), depth, rho, g,
                              version]).encode())
    return digest.hexdigest()[:32]


def capytaine_hydrodynamics(body, spec, environment, z_origin: float, path: str,
                            progress: bool = True) -> Hydrodynamics:
    """``body``'s hydrodynamics from Capytaine at its equilibrium draft (cached)."""
    cpt = _capytaine(path)
    import xarray as xr

    mesh = hull_mesh(cpt, body, z_origin, spec.panel_size)
    depth = float(environment.depth + environment.water_level)
    rho, g = environment.water_density, environment.gravity
    key = _key(mesh, spec, depth, rho, g, cpt.__version__)
    folder = cache_folder(spec)
    file = folder / f"capytaine-{key}.npz"
    with _LOCK:
        if not file.exists():
            fb = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(
                rotation_center=(0.0, 0.0, z_origin)), name=body.name)
            matrix = xr.Dataset(coords={
                "omega": list(spec.omega),
                "wave_direction": [math.radians(b) for b in spec.headings_deg],
                "radiating_dof": list(DOF_NAMES), "water_depth": [depth], "rho": [rho],
                "g": [g]})
            ds = cpt.BEMSolver().fill_dataset(matrix, fb, progress_bar=progress)
            order = ("omega", "influenced_dof", "radiating_dof")
            A = ds["added_mass"].sel(influenced_dof=list(DOF_NAMES),
                                     radiating_dof=list(DOF_NAMES)).transpose(*order)
            B = ds["radiation_damping"].sel(influenced_dof=list(DOF_NAMES),
                                            radiating_dof=list(DOF_NAMES)).transpose(*order)
            X = ds["excitation_force"].sel(influenced_dof=list(DOF_NAMES)).transpose(
                "wave_direction", "omega", "influenced_dof")
            folder.mkdir(parents=True, exist_ok=True)
            tmp = file.with_suffix(".tmp.npz")
            np.savez(tmp, A=np.squeeze(A.values).reshape(-1, 6, 6),
                     B=np.squeeze(B.values).reshape(-1, 6, 6),
                     X=np.conj(np.squeeze(X.values)).reshape(len(spec.headings_deg), -1, 6))
            os.replace(tmp, file)
        data = np.load(file)
        A, B, X = data["A"], data["B"], data["X"]
    excitation = tuple(ExcitationTable(heading_deg=float(h), re=tuple(map(tuple, X[k].real)),
                                       im=tuple(map(tuple, X[k].imag)))
                       for k, h in enumerate(spec.headings_deg))
    return Hydrodynamics(omega=tuple(spec.omega), added_mass=tuple(map(lambda a: tuple(
        map(tuple, a)), A)), damping=tuple(map(lambda b: tuple(map(tuple, b)), B)),
        excitation=excitation, mean_drift=(), source="capytaine")
