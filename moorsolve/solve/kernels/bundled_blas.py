"""One thread for the OpenBLAS that CasADi bundles for IPOPT's linear solver (MUMPS).

A mooring's NLP has tens to hundreds of unknowns. Factorising it on two threads gains no
wall time (the 12-chain dock: 2.56 ms against 2.52 ms per solve), but OpenBLAS's worker
spins between MUMPS's small calls and doubled the CPU time of a solve (5.1 ms against
2.6 ms), taking a core from the other thread of a sweep. So once CasADi has loaded its
OpenBLAS (with the first IPOPT solver), it is set to ``MOORSOLVE_IPOPT_THREADS`` threads
(1 by default; ``0`` leaves OpenBLAS's own choice). Only CasADi's private copy is touched:
numpy's BLAS and the caller's thread settings are not.
"""

from __future__ import annotations

import ctypes
import os
import threading
from pathlib import Path

import casadi as ca

__all__ = ["limit_bundled_blas"]

_DONE = threading.Event()
_LOCK = threading.Lock()


def _threads() -> int:
    text = os.environ.get("MOORSOLVE_IPOPT_THREADS", "1").strip()
    return int(text) if text.isdigit() else 1


def limit_bundled_blas() -> None:
    """Set CasADi's bundled OpenBLAS to ``MOORSOLVE_IPOPT_THREADS`` threads, once, after an
    IPOPT solver has been made (before that the library is not loaded: nothing to set)."""
    if _DONE.is_set():
        return
    with _LOCK:
        if _DONE.is_set():
            return
        n = _threads()
        no_load = getattr(os, "RTLD_NOLOAD", None)      # not on Windows: left alone there
        if n > 0 and no_load is not None:
            folder = Path(ca.__file__).parent
            for path in sorted([*folder.glob("libcasadi-tp-openblas.so*"),
                                *folder.glob("libcasadi-tp-openblas*.dylib")]):
                try:
                    # RTLD_NOLOAD: only the copy IPOPT already loaded, never a new one.
                    lib = ctypes.CDLL(str(path), mode=no_load | os.RTLD_GLOBAL)
                except OSError:
                    continue
                setter = getattr(lib, "openblas_set_num_threads", None)
                if setter is not None:
                    setter(ctypes.c_int(n))
                    # The workers started when the library loaded spin for ~0.1 s of
                    # CPU before they sleep, whatever the new count: end them now (as
                    # OpenBLAS does before a fork; it starts them again if ever needed).
                    shutdown = getattr(lib, "blas_thread_shutdown_", None)
                    if n == 1 and shutdown is not None:
                        shutdown()
                break
        _DONE.set()
