"""CasADi functions generated to C, compiled once, cached on disk and called through ctypes.

Calling a CasADi ``Function`` from Python converts every argument to a ``DM`` and back,
which costs tens of microseconds: more than a whole Newton solve of a 12-leg mooring. Here
the functions are generated to C (``CodeGenerator``), compiled with the system's C compiler
into one shared library, and called through ``ctypes`` with pointers into numpy buffers
allocated once. ``ctypes`` releases the GIL during the call, so threads calling one library
run on separate cores.

The cache lives in ``$MOORSOLVE_CACHE_DIR`` or ``~/.cache/moorsolve``. A library is named
by a *key*: the caller's structural key (:meth:`Library.__init__`: what decides the
generated code, with moorsolve's own source and CasADi's version), so a cached library is
found before any code is generated, or else the hash of the source. It is written to a
temporary name and renamed into place, so concurrent processes never load a partial file.

Compiling a problem of many lines takes seconds to minutes. By default it runs in the
background (``MOORSOLVE_COMPILE=background``): the compiler is a separate process, the
caller keeps using the interpreted Function (the same arithmetic, slower) and switches to
the library when it is ready; a process that exits first leaves the compiler to finish
into the cache for the next run. ``MOORSOLVE_COMPILE=wait`` waits instead, ``off`` (or the
older ``MOORSOLVE_NO_COMPILE``) never compiles. Each compile is logged (INFO) when it
starts and when it ends, with its duration. Without a compiler the Function runs
interpreted and a warning says so.
"""

from __future__ import annotations

import ctypes
import functools
import hashlib
import logging
import os
import queue
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
#: Optimisation levels ``MOORSOLVE_COMPILE_OPT`` may set instead of the size-based one.
OPT_LEVELS = ("-O0", "-O1", "-O2", "-O3")
_LOCK = threading.Lock()
_LOADED: dict[str, ctypes.CDLL] = {}
MODES = ("background", "wait", "off")


def _opt_override() -> str:
    """``MOORSOLVE_COMPILE_OPT`` (one of :data:`OPT_LEVELS`), or "" for the default. The
    test suite compiles at -O0: a quarter of the compile time, the same IEEE arithmetic."""
    level = os.environ.get("MOORSOLVE_COMPILE_OPT", "").strip()
    return level if level in OPT_LEVELS else ""


def cache_dir() -> Path:
    """Where compiled libraries are kept."""
    root = os.environ.get("MOORSOLVE_CACHE_DIR")
    return Path(root) if root else Path.home() / ".cache" / "moorsolve"


def compile_mode() -> str:
    """``MOORSOLVE_COMPILE`` (background, wait or off; background by default)."""
    if os.environ.get("MOORSOLVE_NO_COMPILE"):
        return "off"
    mode = os.environ.get("MOORSOLVE_COMPILE", "background").strip().lower()
    return mode if mode in MODES else "background"


def _compiler() -> list[str] | None:
    cc = os.environ.get("CC") or sysconfig.get_config_var("CC") or "cc"
    argv = shlex.split(cc)
    if argv and shutil.which(argv[0]):
        return argv
    for name in ("cc", "gcc", "clang"):
        if shutil.which(name):
            return [name]
    return None


@functools.lru_cache(maxsize=None)
def code_version() -> str:
    """A hash of the code that builds the compiled graphs (moorsolve's solve/, physics/
    and audit/ sources, and this module) and of CasADi's version: part of every structural
    key."""
    root = Path(__file__).resolve().parent
    digest = hashlib.sha256(ca.__version__.encode())
    for folder in ("solve", "physics", "audit"):
        for path in sorted((root / folder).rglob("*.py")):
            digest.update(path.relative_to(root).as_posix().encode() + path.read_bytes())
    digest.update(Path(__file__).name.encode() + Path(__file__).read_bytes())
    return digest.hexdigest()


def compile_function(fn: ca.Function) -> "CompiledFunction | None":
    """``fn`` as a compiled library (waiting for it), from the disk cache when it is
    there already."""
    library = Library([fn], mode="wait" if compile_mode() != "off" else "off")
    return library.instances()[0] if library.ready else None


def compile_functions(fns: list) -> "list[CompiledFunction] | None":
    """The functions ``fns`` compiled into one library (waiting for it); one
    :class:`CompiledFunction` each, or None."""
    library = Library(fns, mode="wait" if compile_mode() != "off" else "off")
    return library.instances() if library.ready else None


class Library:
    """Functions compiled into one shared library, now or in the background.

    Parameters
    ----------
    fns : list of casadi.Function
        Dense inputs and outputs; the library is named after the first.
    key : str, optional
        What determines the generated code (a structural description, hashed with
        :func:`code_version`): a cached library is then found without generating code.
        Without it the library is named by the hash of its source.
    mode : {"background", "wait", "off"}, optional
        Defaults to :func:`compile_mode`.
    label : str
        How the log names what is compiled (``"the Newton kernel of 48 lines"``).

    Attributes
    ----------
    ready : bool
        The library is loaded; :meth:`instances` gives callable functions.
    """

    def __init__(self, fns: list, key: str | None = None, mode: str | None = None,
                 label: str | None = None):
        self.fns = list(fns)
        self.name = self.fns[0].name()
        self.label = label or self.name
        self.ready = False
        self.failed = False
        self.path: Path | None = None
        self._done = threading.Event()
        mode = compile_mode() if mode is None else mode
        cc = _compiler()
        if mode == "off" or cc is None:
            if cc is None and mode != "off":
                log.warning("no C compiler found; %s runs interpreted", self.label)
            self._finish(None)
            return
        override = _opt_override()
        if key is not None:
            digest = hashlib.sha256((key + code_version() + override).encode()).hexdigest()[:20]
            self.path = cache_dir() / f"{self.name}_s{digest}.so"
            if self.path.exists():
                self._finish(self.path)
                return
        tmp = tempfile.mkdtemp(prefix="moorsolve-")
        source = Path(tmp) / f"{self.name}.c"
        gen = ca.CodeGenerator(source.name, {"with_header": False})
        for fn in self.fns:
            gen.add(fn)
        gen.generate(tmp + os.sep)
        text = source.read_bytes()
        level = override or ("-O2" if len(text) < _LARGE_SOURCE else "-O1")
        flags = (level,) + _FLAGS[1:]
        if self.path is None:
            digest = hashlib.sha256(text + " ".join(cc + list(flags)).encode()
                                    + ca.__version__.encode()).hexdigest()[:20]
            self.path = cache_dir() / f"{self.name}_{digest}.so"
        if self.path.exists():
            shutil.rmtree(tmp, ignore_errors=True)
            self._finish(self.path)
            return
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd, partial = tempfile.mkstemp(suffix=".so", dir=self.path.parent)
        os.close(fd)
        log.info("compiling %s with %s (%d kB of C; once per problem structure, cached in "
                 "%s)%s", self.label, cc[0], len(text) // 1024, cache_dir(),
                 "; solving interpreted meanwhile" if mode == "background" else "")
        job = (self, [*cc, *flags, str(source), "-o", partial, "-lm"], partial, tmp)
        if mode == "wait":
            _compile(*job)
        else:
            _QUEUE.put(job)
            _start_worker()

    def _finish(self, path: Path | None) -> None:
        if path is not None:
            try:
                with _LOCK:
                    if str(path) not in _LOADED:
                        _LOADED[str(path)] = ctypes.CDLL(str(path))
                self.ready = True
            except OSError as error:
                log.warning("loading %s failed (%s); it runs interpreted", path, error)
        self.failed = not self.ready
        self._done.set()

    def wait(self, timeout: float | None = None) -> bool:
        """Wait for a compile in progress; whether the library is ready."""
        self._done.wait(timeout)
        return self.ready

    def instances(self) -> "list[CompiledFunction]":
        """One :class:`CompiledFunction` per function (own buffers), once ready."""
        if not self.ready:
            raise RuntimeError(f"{self.name} is not compiled")
        return [CompiledFunction(fn, self.path) for fn in self.fns]


#: Background compiles, run one at a time by one worker thread (a checks run or a test
#: suite meets many structures; compiling them all at once would swamp the machine).
_QUEUE: "queue.Queue" = queue.Queue()
_WORKER: list = []


def _start_worker() -> None:
    with _LOCK:
        if not _WORKER or not _WORKER[0].is_alive():
            worker = threading.Thread(target=_work, daemon=True, name="moorsolve-compile")
            _WORKER[:] = [worker]
            worker.start()


def _work() -> None:
    while True:
        _compile(*_QUEUE.get())
        _QUEUE.task_done()


def _compile(library: Library, argv: list, partial: str, tmp: str) -> None:
    """Run the compiler into ``partial``, rename it to the library's path and load it."""
    started = time.perf_counter()
    # One shell in its own session compiles, renames into place and tidies up: a compile
    # still running when this process exits finishes into the cache for the next one.
    script = (f"{shlex.join(argv)} && mv -f {shlex.quote(partial)} "
              f"{shlex.quote(str(library.path))}; status=$?; rm -rf {shlex.quote(tmp)}; "
              "exit $status")
    try:
        done = subprocess.run(["sh", "-c", script], stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, start_new_session=True, timeout=3600)
        if done.returncode != 0 or not library.path.exists():
            raise OSError(done.stderr.decode(errors="replace").strip()[-500:]
                          or f"exit status {done.returncode}")
        log.info("compiled %s in %.1f s", library.label, time.perf_counter() - started)
        library._finish(library.path)
    except (OSError, subprocess.SubprocessError) as error:
        log.warning("compiling %s failed (%s); it runs interpreted", library.label, error)
        library._finish(None)
    finally:
        if os.path.exists(partial):
            os.unlink(partial)
        shutil.rmtree(tmp, ignore_errors=True)


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
        #: Name and (rows, columns) of every output, for callers that reshape them.
        self.output_names = fn.name_out()
        self.output_shapes = [fn.sparsity_out(i).shape for i in range(fn.n_out())]
        self.inputs = [np.zeros(fn.nnz_in(i)) for i in range(fn.n_in())]
        # The outputs are views of one buffer, so a caller keeps them all with one copy
        # (:meth:`copy_outputs`).
        sizes = [fn.nnz_out(i) for i in range(fn.n_out())]
        ends = np.cumsum([0] + sizes)
        self._slices = [slice(int(a), int(b)) for a, b in zip(ends[:-1], ends[1:])]
        #: Where each output lies in :attr:`output_buffer`.
        self.output_slices = self._slices
        self.output_buffer = np.zeros(max(int(ends[-1]), 1))
        self.outputs = [self.output_buffer[sl] for sl in self._slices]
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

    def copy_outputs(self, shaped: bool = False) -> list:
        """Copies of the last outputs (one copy of the buffer, then views of it); with
        ``shaped`` a matrix output in its CasADi (column-major) shape, a column flat."""
        buffer = self.output_buffer.copy()
        if not shaped:
            return [buffer[sl] for sl in self._slices]
        # Columns stay flat views; matrices are reshaped (column-major).
        return [buffer[sl] if shape[1] == 1 else buffer[sl].reshape(shape, order="F")
                for sl, shape in zip(self._slices, self.output_shapes)]

    def clone(self) -> "CompiledFunction":
        return CompiledFunction(self.fn, self.library)

    def __call__(self) -> None:
        """Evaluate on the current contents of :attr:`inputs` into :attr:`outputs`."""
        if self._call(*self._args) != 0:
            raise RuntimeError(f"{self.fn.name()} failed")
