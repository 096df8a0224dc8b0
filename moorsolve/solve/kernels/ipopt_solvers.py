"""IPOPT solver objects of one problem: interpreted at first, compiled once it is hot.

CasADi's IPOPT interface evaluates the NLP's functions (residuals, their Jacobian, the
Hessian of the Lagrangian) with its SX interpreter: a fifth to a third of an IPOPT solve of
a mooring. A problem solved with IPOPT :data:`COMPILE_AFTER` times (a sweep, a benchmark,
a hunt) has those functions generated to C and compiled into one library
(:class:`.compiled.Library`: cached on disk by structure, in the background); once it is
loaded, the problem's IPOPT solvers evaluate them compiled (``ca.external``),
the same arithmetic, so the same iterates. A one-off solve never pays for a compile.

Thread safety: a problem's solvers are made and run under its lock (the caller's for
:meth:`IpoptSolvers.get` and :meth:`IpoptSolvers.note_solve`, taken here for
:meth:`IpoptSolvers.compile`); the library loads in the compile worker's thread.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from .bundled_blas import limit_bundled_blas
from ...concurrency import SYMBOLIC_LOCK

__all__ = ["IpoptSolvers", "COMPILE_AFTER"]

#: Solves of one problem with IPOPT after which its NLP functions are compiled. The
#: compile takes 1-11 s of a core (the semis, the dock, three platforms) and saves about
#: 0.1-0.5 ms a solve, so it pays after thousands of solves: a study's, not a CLI run's or
#: a test's (the library is then cached on disk for the next process).
COMPILE_AFTER = 200

#: The functions CasADi's IPOPT interface evaluates (besides ``nlp_f`` and ``nlp_g``,
#: which it derives from the oracle) that the library replaces, by nlpsol option.
_DERIVED = {"grad_f": "nlp_grad_f", "jac_g": "nlp_jac_g", "hess_lag": "nlp_hess_l"}
_PREFIX = "moorsolve_ipopt"


def solver_options(tol: float, max_iter: int, max_time_s: float) -> dict:
    """nlpsol options of the feasibility NLP (both the interpreted and compiled solvers)."""
    return {
        "print_time": False,
        "error_on_fail": False,
        # A NaN or inf met on the way (absurd input) is reported by the certificate and
        # ConvergenceError; CasADi's per-evaluation warnings are noise.
        "show_eval_warnings": False,
        # Only the point is used (the certificate is recomputed from it): no multipliers,
        # objective or constraints recomputed after IPOPT, and no gradient function for
        # them (a compiled oracle has no derivatives to make it from).
        "calc_lam_p": False, "calc_lam_x": False, "calc_f": False, "calc_g": False,
        "no_nlp_grad": True,
        "ipopt": {
            "print_level": 0, "sb": "yes", "tol": tol,
            "constr_viol_tol": tol, "max_iter": max_iter,
            "max_wall_time": max_time_s, "nlp_scaling_method": "none",
            "mu_strategy": "adaptive",
        },
    }


class IpoptSolvers:
    """The IPOPT solvers of one problem, one per setting ``(tol, max_iter, max_time_s)``,
    and the compiled library of its NLP functions."""

    def __init__(self, problem):
        self.problem = problem
        self._interpreted: dict = {}
        self._compiled: dict = {}
        self.solves = 0
        self.library = None
        self._certificate = None

    def nlp(self) -> dict:
        """The NLP: the residuals as equality constraints. Where the scene has
        complementarities IPOPT solves them smoothed (a smoothing parameter appended to
        p, :meth:`~.numerics.SolverAccess.nlp_parameters`; the polish makes them exact)
        and, among the equilibria, takes the one nearest its start (also appended), which
        keeps it from wandering through open contacts and slack hawsers, and pins a
        degree of freedom nothing holds."""
        pr = self.problem
        nlp = {"x": pr._xs, "p": pr._p, "f": 0, "g": pr._g}
        if pr.smoothed:
            start = ca.SX.sym("start", pr.n_x)
            nlp["p"] = ca.vertcat(pr._p, pr.smoothing_symbol, start)
            nlp["g"] = pr._g_smooth
            nlp["f"] = pr.IPOPT_PROXIMITY * ca.sumsqr(pr._xs - start)
        return nlp

    @property
    def compiled(self) -> bool:
        """Whether the solvers now evaluate the NLP's functions compiled."""
        return self.library is not None and self.library.ready

    def get(self, tol: float, max_iter: int, max_time_s: float) -> ca.Function:
        """The solver for a setting: over the compiled library once it is loaded."""
        key = (tol, max_iter, max_time_s)
        if self.compiled:
            if key not in self._compiled:
                self._compiled[key] = self._compiled_solver(key)
            return self._compiled[key]
        return self._solver(key)

    def note_solve(self) -> None:
        """Count a solve of the problem with IPOPT; the :data:`COMPILE_AFTER`-th starts
        the compile."""
        self.solves += 1
        if self.library is None and self.solves >= COMPILE_AFTER:
            self.compile()

    def compile(self, mode: str = "background"):
        """Start compiling the NLP's functions, once (``mode`` "wait" waits for it); the
        :class:`.compiled.Library`.

        In the background whatever ``MOORSOLVE_COMPILE`` says (unless "off"): the compiled
        functions give the same iterates, so nothing is gained by waiting, and a solve
        that waited would spend its time budget on the compiler.
        """
        from ...compiled import Library, compile_mode
        from .newton import COMPILE_MAX_UNKNOWNS
        pr = self.problem
        with pr.lock:
            if self.library is not None:
                return self.library
            # The functions do not depend on the setting: any setting's solver has them.
            solver = next(iter(self._interpreted.values()), None) or self._solver(
                (1e-9, 3000, 60.0))
            with SYMBOLIC_LOCK:
                fns = [_renamed(self._oracle(), _PREFIX)]
                fns += [_renamed(solver.get_function(name), f"{_PREFIX}_{name}")
                        for name in _DERIVED.values()]
                # The certificate too: the strategy certifies every point IPOPT returns.
                fns.append(_renamed(pr.certificate, f"{_PREFIX}_certificate"))
            if pr.n_x > COMPILE_MAX_UNKNOWNS or compile_mode() == "off":
                # Past the size limit as the Newton kernel: minutes of C compiling for a
                # modest gain.
                mode = "off"
            self.library = Library(fns, key=_library_key(pr), mode=mode,
                                   label=f"IPOPT's functions of {pr.n_legs} lines")
            return self.library

    def wait_compiled(self, timeout: float | None = None) -> bool:
        """Compile now if not yet started and wait for it; whether the solvers now run
        compiled."""
        return self.compile().wait(timeout)

    def certify(self, x, p, tol: float) -> bool:
        """``problem.certify(x, p, tol)[0]``: the problem's judgement of its certificate,
        the certificate evaluated by the library once it is loaded (the same arithmetic,
        without an interpreted call's conversions)."""
        pr = self.problem
        if not self.compiled or not np.all(np.isfinite(x)):
            return pr.certify(x, p, tol)[0]
        return pr.judge(*self.certificate_values(x, p), tol=tol)[0]

    def certificate_values(self, x, p) -> list:
        """The certificate's numbers at ``x`` (force, moment, t_max, penetration,
        complementarity), compiled once the library is loaded."""
        if not self.compiled:
            return [float(v) for v in self.problem.certificate(x, p)]
        if self._certificate is None:
            from ...compiled import CompiledFunction
            self._certificate = CompiledFunction(self.library.fns[-1], self.library.path)
        fn = self._certificate
        fn.inputs[0][:] = x
        fn.inputs[1][:] = p
        fn()
        return fn.output_buffer.tolist()

    def _solver(self, key) -> ca.Function:
        """The interpreted solver of a setting."""
        if key not in self._interpreted:
            with SYMBOLIC_LOCK:
                self._interpreted[key] = ca.nlpsol("equilibrium", "ipopt", self.nlp(),
                                                   solver_options(*key))
            limit_bundled_blas()
        return self._interpreted[key]

    def _oracle(self) -> ca.Function:
        nlp = self.nlp()
        return ca.Function("oracle", [nlp["x"], nlp["p"]], [nlp["f"], nlp["g"]],
                           ["x", "p"], ["f", "g"])

    def _compiled_solver(self, key) -> ca.Function:
        """The nlpsol of a setting over the compiled library."""
        path = str(self.library.path)
        opts = solver_options(*key)
        with SYMBOLIC_LOCK:
            for option, name in _DERIVED.items():
                opts[option] = ca.external(f"{_PREFIX}_{name}", path)
            return ca.nlpsol("equilibrium", "ipopt", ca.external(_PREFIX, path), opts)


def _renamed(fn: ca.Function, name: str) -> ca.Function:
    """An SX function under another name (the library's symbols are the names)."""
    args = fn.sx_in()
    return ca.Function(name, args, fn.call(args), fn.name_in(), fn.name_out())


def _library_key(problem) -> str:
    """What decides the generated code: the problem's structure, scales and sizes (the
    scales are constants in the graph) and whether, and how, it is smoothed
    (:class:`.compiled.Library` adds the code version)."""
    from ..assembly.prepared import structure_key
    return repr(("ipopt-nlp", structure_key(problem.case), problem.force_scale,
                 problem.length_scale, problem.moment_scale, problem.n_x, problem.n_p,
                 problem.smoothed, problem.IPOPT_PROXIMITY))
