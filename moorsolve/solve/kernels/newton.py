"""The fast path: a damped Newton method on the equilibrium residuals, as one CasADi graph.

The whole iteration (residuals, Jacobian, sparse QR solve, step limit, projection onto the
bounds and a backtracking line search) is written as a CasADi ``Function`` of
``(x0, p, tol)``. The loop is unrolled to a fixed number of iterations, each guarded by a
conditional (``Function.if_else``), so a converged point skips the remaining work. The
function is generated to C and compiled once (:mod:`.compiled`), then called without
Python in the loop; without a compiler the same Function runs interpreted.

Iteration, on the scaled unknowns of :class:`~.problem.EquilibriumProblem`:

1. ``g, J`` at ``x``. Stop when the certificate, estimated from ``g`` and ``J`` (each
   leg's span mismatch converted to fairlead force through its own 2x2 block; the body's
   unbalanced force and moment), is within ``tol`` of the largest fairlead tension.
2. ``d = J \\ g`` (sparse QR), scaled so that no component moves by more than its limit
   (:data:`STEP_LIMIT`: one depth in position, one radian; :data:`LINE_STEP_LIMIT`: four
   typical tensions).
3. Backtrack ``x - a d``, ``a = 1, 1/2, ...``, projected onto the bounds (hanging lines
   keep ``u >= 0`` so ``H >= 0``), until the squared residual norm
   drops by the Armijo factor ``1 - 2e-4 a`` (with complementarities: or does not grow,
   which is progress while a body crosses free space toward a support). No acceptable
   step: the method has stalled.

The exact certificate of the final point (:meth:`EquilibriumProblem.certify`) is part of
the outputs, and so are the body position and the leg tensions a sweep records.
"""

from __future__ import annotations

import logging
import math

import casadi as ca
import numpy as np

# The largest problem (unknowns) whose kernel is compiled; beyond, scenes without
# complementarities take the sparse path (:mod:`.sparse_newton`).
from .sparse_stiffness import COMPILE_MAX_UNKNOWNS

log = logging.getLogger(__name__)

#: Most node unknowns whose Schur complement is solved symbolically (beyond: sparse QR).
_ARROW_NODES = 24
#: Largest change of a scaled body or point unknown in one Newton step (one depth, one
#: radian), and of a line's (a tension's: four typical tensions). The whole step is scaled
#: down to the tightest, so it stays a Newton direction (a descent direction for the line
#: search). A line's tension may need several typical tensions from rest under a large
#: load: at one, the 12-chain dock under up to 9 MN took 9.7 iterations, at four 8.2.
STEP_LIMIT = 1.0
LINE_STEP_LIMIT = 4.0
#: Unrolled iterations; a point still unconverged after them reports status 2.
MAX_ITERATIONS = 40
_BACKTRACKS = 12
_FREE_BACKTRACKS = 24
_ARMIJO = 1e-4
#: A step that leaves the squared residual within this fraction of where it was counts as
#: not growing it (round-off in a body's balance as it crosses free space).
FLAT = 1e-10

#: Status codes of the kernel.
CONVERGED, STALLED, MAX_ITER = 0, 1, 2
STATUS_TEXT = {CONVERGED: "Newton converged", STALLED: "Newton stalled (no descent step)",
               MAX_ITER: "Newton reached its iteration limit"}


def newton_step_function(problem) -> ca.Function:
    """``(g, J) -> J \\ g`` exploiting the Jacobian's arrow structure when it has it.

    Each leg's two span residuals depend only on its own ``(u, V)`` and on the body
    position, so ``J = [[A, B], [C, D]]`` with ``A`` block diagonal (2x2 per leg). Block
    elimination then costs O(legs): per leg an explicit 2x2 inverse, and one Schur
    complement of the size of the body's free DOFs. A problem without that structure
    (or with a singular leg block, which gives a non-finite step and stalls the line
    search, so the caller falls back to IPOPT) uses CasADi's sparse QR.
    """
    n, n_q, n_legs = problem.n_x, problem.n_q, problem.n_legs
    sp = problem.step_sparsity()
    g = ca.SX.sym("g", n)
    J = ca.SX.sym("J", sp)
    rows, cols = sp.get_triplet()
    # Multi-segment legs have more unknowns per leg: no arrow structure then.
    # Complementarities (hawsers, contacts) take the regularised sparse QR step.
    arrow = (not problem.smoothed and problem.n_x == n_q + 2 * n_legs
             and n_q <= _ARROW_NODES and all(c < n_q or r >= 2 * n_legs
                                             or (c - n_q) // 2 == r // 2
                                             for r, c in zip(rows, cols)))
    if not arrow:
        Jm, gm = ca.MX.sym("J", sp), ca.MX.sym("g", n)
        return ca.Function("newton_qr", [gm, Jm], [ca.solve(Jm, gm, "qr")])
    S = J[2 * n_legs:, :n_q] if n_q else None
    r_body = g[2 * n_legs:] if n_q else None
    Y, Z = [], []
    for i in range(n_legs):
        r, c = 2 * i, n_q + 2 * i
        a, b, cc, d = J[r, c], J[r, c + 1], J[r + 1, c], J[r + 1, c + 1]
        det = a * d - b * cc
        inv = ca.vertcat(ca.horzcat(d, -b), ca.horzcat(-cc, a)) / det
        y = inv @ g[r:r + 2]
        Y.append(y)
        if n_q:
            z = inv @ J[r:r + 2, :n_q]
            Z.append(z)
            C = J[2 * n_legs:, c:c + 2]
            S = S - C @ z
            r_body = r_body - C @ y
    if n_q:
        dq = ca.solve(S, r_body)
        dl = [y - z @ dq for y, z in zip(Y, Z)]
        step = ca.vertcat(dq, *dl)
    else:
        step = ca.vertcat(*Y)
    return ca.Function("newton_arrow", [g, J], [step])


def newton_function(problem, max_iterations: int = MAX_ITERATIONS) -> ca.Function:
    """``newton(x0, p, tol) -> (x, status, iterations, certificate, body, t_fair, t_anchor,
    reactions)``.

    ``certificate`` is ``[force_N, moment_Nm, t_max_N, penetration_m, complementarity_N]``;
    ``body`` is ``[x_m, y_m, yaw]``.
    """
    n, n_q, n_legs = problem.n_x, problem.n_q, problem.n_legs
    fs = problem.force_scale
    lb, ub = (np.where(np.isfinite(b), b, s * 1e30) for b, s in zip(problem.bounds(), (-1, 1)))
    x = ca.MX.sym("x", n)
    p = ca.MX.sym("p", problem.n_p)
    tol = ca.MX.sym("tol")
    g_sym = ca.MX.sym("g", n)
    J_sym = ca.MX.sym("J", problem.step_sparsity())

    # -- the certificate estimate from g and J -----------------------------------------
    if problem.smoothed:
        # Jacobian smoothing: the exact residual, the Jacobian of the smoothed
        # complementarities with eps tied to it (EquilibriumProblem.step_jacobian).
        g = problem.residual(x, p)
        eps = problem.SMOOTHING * problem.length_scale * ca.fmin(1, ca.mmax(ca.fabs(g)))
        J = ca.project(problem.smoothed_jacobian(x, p, eps) - problem.regularisation(),
                       problem.step_sparsity())
    else:
        g, J = problem.residual_jacobian(x, p)
    if problem.n_x == n_q + 2 * n_legs and not problem.smoothed:
        forces, moment = [], ca.MX(0)
        for i in range(n_legs):
            r, c = 2 * i, n_q + 2 * i
            block = J[r:r + 2, c:c + 2]
            det = block[0, 0] * block[1, 1] - block[0, 1] * block[1, 0]
            du = block[1, 1] * g[r] - block[0, 1] * g[r + 1]
            dv = -block[1, 0] * g[r] + block[0, 0] * g[r + 1]
            forces.append(fs * ca.hypot(du, dv) / ca.fabs(det))
        for k, rotational in enumerate(problem.rotational):
            value = ca.fabs(g[2 * n_legs + k])
            if rotational:
                moment = ca.fmax(moment, value * problem.moment_scale)
            else:
                forces.append(value * fs)
        xp = x * ca.DM(problem.x_scale)
        fair_t = [ca.hypot(ca.fmax(xp[n_q + 2 * i], 0), xp[n_q + 2 * i + 1])
                  for i in range(n_legs)]
        t_est = ca.fmax(ca.mmax(ca.vertcat(*fair_t)), fs * 1e-12) if fair_t else ca.MX(fs)
        force = ca.mmax(ca.vertcat(*forces)) if forces else ca.MX(0)
    else:
        # Multi-segment legs, contacts: the exact certificate (its layout differs).
        force, moment, t_max, penetration, complementarity = problem.certificate(x, p)
        t_est = ca.fmax(t_max, fs * 1e-12)
        force = ca.fmax(force, complementarity)
        # A penetration beyond tol x the length scale counts as an unbalanced force.
        force = ca.if_else(penetration <= tol * problem.length_scale, force, ca.inf)
    converged = ca.logic_and(force <= tol * t_est,
                             moment <= tol * t_est * problem.moment_scale / fs)
    # NaN compares false, so a NaN state is never "converged".
    evaluate = ca.Function("newton_eval", [x, p, tol], [g, J, converged])

    # -- backtracking line search as a chain of conditionals ----------------------------
    d_sym = ca.MX.sym("d", n)
    m0 = ca.MX.sym("m0")

    def trial(j: int, flat: bool, tag: str, tries: int = _BACKTRACKS) -> ca.Function:
        a = 0.5 ** j
        xa = ca.fmin(ca.fmax(x - a * d_sym, lb), ub)
        ma = ca.sumsqr(problem.residual(xa, p))
        accept = ma <= (1 - 2 * _ARMIJO * a) * m0
        if flat:
            accept = ca.logic_or(accept, ma <= (1 + FLAT) * m0)
        xa_sym = ca.MX.sym("xa", n)
        take = ca.Function(f"newton_take{tag}{j}", [x, d_sym, p, m0, xa_sym], [xa_sym, 0])
        if j + 1 < tries:
            nxt = trial(j + 1, flat, tag, tries)
            more = ca.Function(f"newton_more{tag}{j}", [x, d_sym, p, m0, xa_sym],
                               nxt(x, d_sym, p, m0))
        else:
            more = ca.Function(f"newton_stall{tag}{j}", [x, d_sym, p, m0, xa_sym], [x, 1])
        branch = ca.Function.if_else(f"newton_ls{tag}{j}", take, more)
        return ca.Function(f"newton_trial{tag}{j}", [x, d_sym, p, m0],
                           branch(accept, x, d_sym, p, m0, xa))

    search = trial(0, False, "")

    # -- one iteration: converged -> done, else step ------------------------------------
    step_fn = newton_step_function(problem)
    step = step_fn(g_sym, J_sym)
    inverse_limit = ca.DM(_inverse_step_limits(problem))

    def limited(d):
        return d * ca.fmin(1, 1 / ca.mmax(ca.fabs(d) * inverse_limit))

    step = limited(step)
    x_new, stalled = search(x, step, p, ca.sumsqr(g_sym))
    if problem.smoothed:
        # No descent along the smoothed Newton step: a body crossing free space toward a
        # support it does not yet touch (a collar within its clearance, a slack hawser)
        # leaves the residual unchanged, and the smoothing may hold it back. Step along the
        # exact Newton direction instead, with a spring on the node unknowns as strong as
        # the residual is large (a pseudo-time step): it moves what nothing holds with its
        # unbalanced force, and a step that does not grow the residual is accepted.
        spring = ca.fmax(problem.REGULARISATION, ca.mmax(ca.fabs(g_sym)))
        J_exact = ca.project(problem.jacobian(x, p) - spring * problem.regularisation(1.0),
                             problem.step_sparsity())
        free_step = limited(step_fn(g_sym, J_exact))
        # Down to a few micrometres: the next support may be that close.
        x_free, stalled_free = trial(0, True, "free", _FREE_BACKTRACKS)(
            x, free_step, p, ca.sumsqr(g_sym))
        xn_sym, st_sym = ca.MX.sym("xn", n), ca.MX.sym("st")
        free = ca.Function("newton_free", [x, p, g_sym, xn_sym, st_sym],
                           [x_free, stalled_free])
        keep = ca.Function("newton_keep", [x, p, g_sym, xn_sym, st_sym], [xn_sym, st_sym])
        x_new, stalled = ca.Function.if_else("newton_fallback", free, keep)(
            stalled, x, p, g_sym, x_new, stalled)
    it = ca.MX.sym("it")
    do_step = ca.Function("newton_step", [x, p, g_sym, J_sym, it],
                          [x_new, 0, stalled, it + 1 - stalled])
    finish = ca.Function("newton_finish", [x, p, g_sym, J_sym, it], [x, 1, 0, it])
    choose = ca.Function.if_else("newton_choose", finish, do_step)
    g_e, J_e, conv_e = evaluate(x, p, tol)
    iterate = ca.Function("newton_iterate", [x, p, tol, it], choose(conv_e, x, p, g_e, J_e, it))

    done_sym, stall_sym = ca.MX.sym("done"), ca.MX.sym("stall")
    active_fn = ca.Function("newton_active", [x, p, tol, done_sym, stall_sym, it],
                            iterate(x, p, tol, it))
    idle_fn = ca.Function("newton_idle", [x, p, tol, done_sym, stall_sym, it],
                          [x, done_sym, stall_sym, it])
    guard = ca.Function.if_else("newton_guard", active_fn, idle_fn)

    xk, done, stall, count = x, ca.MX(0), ca.MX(0), ca.MX(0)
    for _ in range(max_iterations):
        active = ca.logic_and(ca.logic_not(done), ca.logic_not(stall))
        xk, done, stall, count = guard(active, xk, p, tol, done, stall, count)
    status = ca.if_else(done, CONVERGED, ca.if_else(stall, STALLED, MAX_ITER))
    cert = ca.vertcat(*problem.certificate(xk, p))
    body, t_fair, t_anchor, reactions = problem.summary(xk, p)
    # The stability test of the point reached (1: clearly stable; see .stability), so a
    # sweep judges each point without another call.
    # The condensed stiffness goes out too: a sweep row carries its smallest eigenvalue.
    from ..stability.static import clearly_stable_graph, stiffness_graph
    if problem.smoothed:
        n_keep = sum(owner == "body" for owner, _, _ in problem.nodes)
        stable, K = ca.MX(0), ca.MX(ca.DM.nan(n_keep * n_keep, 1))
    else:
        K = stiffness_graph(problem, problem.jacobian(xk, p))
        stable, K = clearly_stable_graph(problem, K), ca.vec(K)
    return ca.Function("moorsolve_newton", [x, p, tol],
                       [xk, status, count, cert, body, t_fair, t_anchor, reactions, stable, K],
                       ["x0", "p", "tol"], list(_OUTPUTS))


def _inverse_step_limits(problem) -> list:
    """1 / the step limit of each scaled unknown: :data:`LINE_STEP_LIMIT` for a line's
    tensions, :data:`STEP_LIMIT` for everything else (bodies, points, a lumped line's node
    positions, a joint's height, the contacts' reactions)."""
    out = [1.0 / STEP_LIMIT] * problem.n_q
    for kind in problem.kinds:
        # A kind lists its unknowns' scales, force or length: here the inverse limits.
        out += kind.scales(1.0 / LINE_STEP_LIMIT, 1.0 / STEP_LIMIT)
    return out + [1.0 / STEP_LIMIT] * (problem.n_x - len(out))


def kernel_key(problem) -> str:
    """What decides the kernel's generated code: the problem's structure, its scales and
    sizes and the kernel's constants (:class:`.compiled.Library` adds the code version)."""
    from ..assembly.prepared import structure_key
    return repr((structure_key(problem.case), problem.force_scale, problem.length_scale,
                 problem.moment_scale, problem.n_x, problem.n_p, MAX_ITERATIONS,
                 _BACKTRACKS, _ARMIJO, STEP_LIMIT, LINE_STEP_LIMIT, _ARROW_NODES))


#: Outputs of the kernel (:func:`newton_function`).
_OUTPUTS = ("x", "status", "iterations", "certificate", "body", "fairlead_tension",
            "anchor_tension", "reactions", "clearly_stable", "stiffness")


class NewtonKernel:
    """The Newton function of one problem, compiled when a C compiler is available.

    The compiled library is called through ctypes with no per-call conversion; until it
    is ready (a first compile runs in the background, :class:`.compiled.Library`) and
    without a compiler the same CasADi Function runs interpreted. ``compiled`` tells which
    the next call uses; :meth:`wait_compiled` waits for a compile in progress.
    """

    def __init__(self, problem, *, compile: bool = True):
        from ...compiled import Library

        self.problem = problem
        self.function = newton_function(problem)
        label = f"the Newton kernel of {problem.n_legs} lines"
        if compile and problem.n_x > COMPILE_MAX_UNKNOWNS:
            # Its C would take minutes to compile for about twice the speed: it stays
            # interpreted (its time per solve grows linearly, as compiled).
            log.info("%s runs interpreted: %d unknowns (compiling stops past %d)", label,
                     problem.n_x, COMPILE_MAX_UNKNOWNS)
            compile = False
        # The problem's post function (certificate, stiffness, report) goes into the
        # same library: a solved point becomes a Result without an interpreted call.
        self._library = Library(
            [self.function, problem.post_function()], key=kernel_key(problem),
            label=label, mode=None if compile else "off")
        self._lib = self._post = None

    @property
    def compiled(self) -> bool:
        """Whether calls run the compiled library (switching to it once it is ready)."""
        if self._lib is None and self._library.ready:
            self._lib, self._post = self._library.instances()
        return self._lib is not None

    def wait_compiled(self, timeout: float | None = None) -> bool:
        """Wait for a compile in progress; whether the kernel now runs compiled."""
        self._library.wait(timeout)
        return self.compiled

    def clone(self) -> "NewtonKernel":
        """A kernel over the same library with its own buffers, for another thread."""
        other = object.__new__(NewtonKernel)
        other.problem, other.function = self.problem, self.function
        other._library, other._lib, other._post = self._library, None, None
        return other

    def _interpreted(self, x0: np.ndarray, p: np.ndarray, tol: float) -> list[np.ndarray]:
        """The kernel run by CasADi's interpreter. Its sparse QR refuses an exactly
        singular step matrix (a slack line whose blocks lose rank mid-iteration) by failing
        the whole evaluation, where the compiled code takes a non-finite step that the line
        search rejects: both end as a stall at the start point, which every caller treats
        as not certified (and falls back to IPOPT)."""
        try:
            return [np.asarray(v, dtype=float).ravel() for v in self.function(x0, p, tol)]
        except RuntimeError as error:
            log.debug("interpreted Newton kernel failed (%s): reported as a stall", error)
        fn = self.function
        out = [np.full(fn.numel_out(k), math.inf if name == "certificate" else math.nan)
               for k, name in enumerate(_OUTPUTS)]
        out[0] = np.array(x0, dtype=float).ravel()
        out[1][:], out[2][:] = STALLED, 0
        out[_OUTPUTS.index("clearly_stable")][:] = 0
        return out

    def post(self, x: np.ndarray, p: np.ndarray) -> dict:
        """The problem's post function (:meth:`EquilibriumProblem.post_function`) at
        ``x``, compiled: fresh numpy arrays by output name, in their CasADi shapes."""
        lib = self._post
        lib.inputs[0][:] = x
        lib.inputs[1][:] = p
        lib()
        return dict(zip(lib.output_names, lib.copy_outputs(shaped=True)))

    def run_many(self, x0: np.ndarray, P: np.ndarray, tol: float) -> dict:
        """The kernel from ``x0`` at every row of ``P`` (a parameter vector each): every
        output as an array with one row per run (a load table's rows)."""
        if not self.compiled:
            runs = [self.raw(x0, p, tol) for p in P]
            return {name: np.array([r[k] for r in runs]) for k, name in enumerate(_OUTPUTS)}
        lib = self._lib
        out = np.empty((len(P), lib.output_buffer.size))
        lib.inputs[0][:] = x0
        lib.inputs[2][0] = tol
        for row, p in enumerate(P):
            lib.inputs[1][:] = p
            lib()
            out[row] = lib.output_buffer
        return {name: out[:, sl] for name, sl in zip(_OUTPUTS, lib.output_slices)}

    def raw(self, x0: np.ndarray, p: np.ndarray, tol: float) -> list[np.ndarray]:
        """Run the kernel; its outputs in order, as views of this kernel's buffers
        (overwritten by the next call) when compiled. For tight loops."""
        if not self.compiled:
            return self._interpreted(x0, p, tol)
        lib = self._lib
        lib.inputs[0][:] = x0
        lib.inputs[1][:] = p
        lib.inputs[2][0] = tol
        lib()
        return lib.outputs

    def solve(self, x0: np.ndarray, p: np.ndarray, tol: float) -> dict:
        """Run the kernel; the outputs as numpy arrays (copies) keyed by name."""
        names = _OUTPUTS
        if self.compiled:
            lib = self._lib
            lib.inputs[0][:] = x0
            lib.inputs[1][:] = p
            lib.inputs[2][0] = tol
            lib()
            values = lib.copy_outputs()
        else:
            values = self._interpreted(x0, p, tol)
        out = dict(zip(names, values))
        out["status"] = int(out["status"][0])
        out["iterations"] = int(out["iterations"][0])
        return out


class KernelPool:
    """Newton kernels of one problem, one per concurrently running caller: each clone has
    its own buffers over the same compiled library."""

    def __init__(self, kernel: NewtonKernel):
        import threading
        self._base, self._free, self._lock = kernel, [kernel], threading.Lock()

    def acquire(self) -> NewtonKernel:
        with self._lock:
            return self._free.pop() if self._free else self._base.clone()

    def release(self, kernel: NewtonKernel) -> None:
        with self._lock:
            self._free.append(kernel)
