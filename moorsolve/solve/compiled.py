"""CasADi functions generated to C, compiled once, cached on disk and called through ctypes.

Calling a CasADi ``Function`` from Python converts every argument to a ``DM`` and back,
which costs tens of microseconds: more than a whole Newton solve of a 12-leg mooring. Here
the function is generated to C (``Function.generate``), compiled with the system's C
compiler into a shared library named by the hash of its source, and called through
``ctypes`` with pointers into numpy buffers allocated once. ``ctypes`` releases the GIL
during the call, so threads calling one library run on separate cores.

The cache lives in ``$MOORSOLVE_CACHE_DIR`` or ``~/.cache/moorsolve``. A library is written
to a temporary name and renamed into place, so concurrent processes never load a partial
file. When no compiler is available the caller falls back to the interpreted Function
(the same arithmetic, slower); :func:`compile_function` returns ``None`` and logs why.
"""

from __future__ import annotations

import ctypes
import hashlib
import logging
import os
import shlex
import shutil
import subprocess
import sysconfig
import tempfile
import threading
import time
from pathlib import Path

import casadi as ca
import numpy as np

log = logging.getLogger(__name__)

_CINT = ctypes.c_longlong          # CasADi's generated casadi_int
_REAL_P = ctypes.POINTER(ctypes.c_double)
_FLAGS = ("-O2", "-fPIC", "-shared")
# Past this size (hundreds of legs) -O2 takes minutes for little gain over -O1.
_LARGE_SOURCE = 1_500_000
_LOCK = threading.Lock()
_LOADED: dict[str, ctypes.CDLL] = {}


def cache_dir() -> Path:
    """Where compiled libraries are kept."""
    root = os.environ.get("MOORSOLVE_CACHE_DIR")
    return Path(root) if root else Path.home() / ".cache" / "moorsolve"


def _compiler() -> list[str] | None:
    cc = os.environ.get("CC") or sysconfig.get_config_var("CC") or "cc"
    argv = shlex.split(cc)
    if argv and shutil.which(argv[0]):
        return argv
    for name in ("cc", "gcc", "clang"):
        if shutil.which(name):
            return [name]
    return None


def compile_function(fn: ca.Function) -> "CompiledFunction | None":
    """``fn`` as a compiled library, from the disk cache when it is there already."""
    if os.environ.get("MOORSOLVE_NO_COMPILE"):
        return None
    cc = _compiler()
    if cc is None:
        log.warning("no C compiler found; %s runs interpreted", fn.name())
        return None
    name = fn.name()
    with tempfile.TemporaryDirectory() as tmp:
        source = Path(tmp) / f"{name}.c"
        gen = ca.CodeGenerator(source.name, {"with_header": False})
        gen.add(fn)
        gen.generate(tmp + os.sep)
        text = source.read_bytes()
        flags = _FLAGS if len(text) < _LARGE_SOURCE else ("-O1",) + _FLAGS[1:]
        digest = hashlib.sha256(text + " ".join(cc + list(flags)).encode()
                                + ca.__version__.encode()).hexdigest()[:20]
        target = cache_dir() / f"{name}_{digest}.so"
        with _LOCK:
            if not target.exists():
                # Announced: a first solve of a new problem structure waits for this.
                log.info("compiling %s with %s (%d kB of C; once per problem structure, "
                         "cached in %s)", name, cc[0], len(text) // 1024, cache_dir())
                t0 = time.perf_counter()
                try:
                    _build(cc, flags, source, target)
                except (OSError, subprocess.SubprocessError) as err:
                    log.warning("compiling %s failed (%s); it runs interpreted", name, err)
                    return None
                log.info("compiled %s in %.1f s", name, time.perf_counter() - t0)
    return CompiledFunction(fn, target)


def _build(cc: list[str], flags: tuple, source: Path, target: Path) -> None:
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, partial = tempfile.mkstemp(suffix=".so", dir=target.parent)
    os.close(fd)
    try:
        subprocess.run([*cc, *flags, str(source), "-o", partial, "-lm"], check=True,
                       capture_output=True, timeout=300)
        os.replace(partial, target)
    finally:
        if os.path.exists(partial):
            os.unlink(partial)


class CompiledFunction:
    """A compiled CasADi function with dense numpy input and output buffers.

    Each instance owns its buffers and work arrays, so one instance serves one thread;
    :meth:`clone` makes another over the same library.
    """

    def __init__(self, fn: ca.Function, library: Path):
        self.fn = fn
        self.library = library
        key = str(library)
        if key not in _LOADED:
            _LOADED[key] = ctypes.CDLL(key)
        lib = _LOADED[key]
        name = fn.name()
        self._call = getattr(lib, name)
        self._call.restype = ctypes.c_int
        sizes = [_CINT() for _ in range(4)]
        getattr(lib, f"{name}_work")(*[ctypes.byref(s) for s in sizes])
        n_arg, n_res, n_iw, n_w = (s.value for s in sizes)
        for i in range(fn.n_in()):
            if not fn.sparsity_in(i).is_dense():
                raise ValueError(f"input {fn.name_in(i)} of {name} must be dense")
        for i in range(fn.n_out()):
            if not fn.sparsity_out(i).is_dense():
                raise ValueError(f"output {fn.name_out(i)} of {name} must be dense")
        self.inputs = [np.zeros(fn.nnz_in(i)) for i in range(fn.n_in())]
        self.outputs = [np.zeros(fn.nnz_out(i)) for i in range(fn.n_out())]
        self._iw = np.zeros(max(n_iw, 1), dtype=np.int64)
        self._w = np.zeros(max(n_w, 1))
        arg = (_REAL_P * max(n_arg, 1))()
        for i, a in enumerate(self.inputs):
            arg[i] = a.ctypes.data_as(_REAL_P)
        res = (_REAL_P * max(n_res, 1))()
        for i, r in enumerate(self.outputs):
            res[i] = r.ctypes.data_as(_REAL_P)
        self._args = (arg, res, self._iw.ctypes.data_as(ctypes.POINTER(_CINT)),
                      self._w.ctypes.data_as(_REAL_P), 0)

    def clone(self) -> "CompiledFunction":
        return CompiledFunction(self.fn, self.library)

    def __call__(self) -> None:
        """Evaluate on the current contents of :attr:`inputs` into :attr:`outputs`."""
        if self._call(*self._args) != 0:
            raise RuntimeError(f"{self.fn.name()} failed")
