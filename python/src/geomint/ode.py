"""ODEs: the method table, built-in and user problems, the integrator and `run`.

Everything numerical happens in libgeomint; this module checks arguments (shapes, dtypes,
NaN) before they reach C and shapes the results as NumPy arrays.
"""
import math
import numbers
import os
import tempfile
import time

import numpy as np

from . import _core
from ._core import Error
from .progress import resolve as _resolve_progress

Problem = (_core.Model, _core.Problem)


# ---- argument checks (raised before any C call) --------------------------------------------

def _vector(name, x, n=None):
    """x as a 1-D float64 array of n finite values; TypeError/ValueError naming `name`."""
    a = np.asarray(x)
    if a.dtype.kind not in "fiu" or a.dtype == np.bool_:
        raise TypeError(f"{name}: expected real numbers, got an array of dtype {a.dtype}")
    if a.ndim != 1:
        raise ValueError(f"{name}: expected a 1-D array, got shape {a.shape}")
    if n is not None and a.shape[0] != n:
        raise ValueError(f"{name}: expected {n} values, got {a.shape[0]}")
    a = np.ascontiguousarray(a, dtype=np.float64)
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        raise ValueError(f"{name}: component {bad[0]} is {a[bad[0]]} (values must be finite)")
    return a


def _real(name, x, positive=False):
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise TypeError(f"{name}: expected a real number, got {type(x).__name__}")
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"{name}: must be finite, got {x}")
    if positive and x <= 0:
        raise ValueError(f"{name}: must be positive, got {x}")
    return x


def _count(name, n):
    if isinstance(n, bool) or not isinstance(n, numbers.Integral):
        raise TypeError(f"{name}: expected an integer, got {type(n).__name__}")
    if n < 0:
        raise ValueError(f"{name}: must be >= 0, got {n}")
    return int(n)


def _callable(name, f, required=True):
    if f is None and not required:
        return None
    if not callable(f):
        raise TypeError(f"{name}: expected a callable, got {type(f).__name__}")
    return f


# ---- tables --------------------------------------------------------------------------------

def methods():
    """The method table: a list of dicts with name, family, order, stages, flags
    ("symplectic", "symmetric", "explicit", ...), accepts (problem kinds), description,
    reference and basic (the basic method of a composition)."""
    return _core.methods()


def method(name):
    """The row of one method (also gauss-S and lobatto-iiia-iiib-S beyond the table);
    geomint.Error with suggestions for an unknown name."""
    if not isinstance(name, str):
        raise TypeError(f"name: expected a str, got {type(name).__name__}")
    return _core.method(name)


def problems():
    """The built-in problems: a list of dicts with name, description, kind, dim,
    params [(name, default, description)], invariants and has_exact."""
    return _core.problems()


def problem(name, set=None):
    """A built-in problem by name, its parameters and initial values (q1.., p1.., y1..) in
    `set`, e.g. problem("kepler", set={"e": 0.9}). The same names as `geomint run --set`."""
    if not isinstance(name, str):
        raise TypeError(f"name: expected a str, got {type(name).__name__}")
    if set is not None:
        if not isinstance(set, dict):
            raise TypeError("set: expected a dict of parameter names to values")
        for k, v in set.items():
            if not isinstance(v, str):
                _real(f"set[{k!r}]", v)
    return _core.Model(name, set)


def _state(q0, p0, y0, need_momenta):
    if need_momenta:
        if y0 is not None:
            raise ValueError("give q0 and p0 (not y0) for a problem in (q, p)")
        q = _vector("q0", q0)
        p = _vector("p0", p0, q.shape[0])
        return q.shape[0], np.concatenate([q, p])
    y = _vector("y0", y0)
    return y.shape[0], y


def separable(V, grad_V, q0, p0, T=None, grad_T=None, t0=0.0):
    """H = T(p) + V(q) from Python callables of one 1-D array each: V(q) -> float,
    grad_V(q) -> array; T, grad_T default to T = |p|^2/2. The arrays passed are read-only
    and reused between calls: copy them to keep them. Vectorized NumPy code is called once
    per force evaluation on the whole state."""
    _callable("V", V)
    _callable("grad_V", grad_V)
    _callable("T", T, False)
    _callable("grad_T", grad_T, False)
    if (T is None) != (grad_T is None):
        raise ValueError("give both T and grad_T, or neither (T = |p|^2/2)")
    dim, y = _state(q0, p0, None, True)
    return _core.Problem("separable", dim, _real("t0", t0), y, grad_V, V, grad_T, T)


def hamiltonian(H, dH_dq, dH_dp, q0, p0, t0=0.0):
    """A general Hamiltonian H(q, p) with its gradients dH_dq(q, p), dH_dp(q, p)."""
    for n, f in (("H", H), ("dH_dq", dH_dq), ("dH_dp", dH_dp)):
        _callable(n, f)
    dim, y = _state(q0, p0, None, True)
    return _core.Problem("hamiltonian", dim, _real("t0", t0), y, H, dH_dq, dH_dp)


def lagrangian(L, dL_dq, dL_dv, q0, v0, t0=0.0):
    """A Lagrangian L(q, v) with its derivatives dL_dq(q, v), dL_dv(q, v), for the
    variational integrators (vi-*). The state is (q, p) with p = dL_dv(q0, v0) at the start;
    second derivatives are taken by central differences where Newton needs them (counted in
    stats["fd_jacobians"])."""
    for n, f in (("L", L), ("dL_dq", dL_dq), ("dL_dv", dL_dv)):
        _callable(n, f)
    q = _vector("q0", q0)
    v = _vector("v0", v0, q.shape[0])
    p = _vector("dL_dv(q0, v0)", dL_dv(q.copy(), v.copy()), q.shape[0])
    return _core.Problem("lagrangian", q.shape[0], _real("t0", t0), np.concatenate([q, p]),
                         L, dL_dq, dL_dv)


def first_order(f, y0, t0=0.0, jacobian=None):
    """y' = f(t, y) with f returning an array of len(y0); jacobian(t, y) -> (n, n) optional."""
    _callable("f", f)
    _callable("jacobian", jacobian, False)
    dim, y = _state(None, None, y0, False)
    return _core.Problem("first-order", dim, _real("t0", t0), y, f, jacobian)


def poisson(H, grad_H, S, y0, hessian=None, t0=0.0):
    """A Poisson system y' = S(y) grad_H(y) from callables of one 1-D array: H(y) -> float,
    grad_H(y) -> array, S(y) -> (n, n) skew array (a Lie–Poisson structure such as the rigid
    body's Π ↦ Π̂), hessian(y) -> (n, n) optional (central differences otherwise). For the
    Poisson rows (discrete gradients, implicit midpoint, Gauss, ...)."""
    for n, f in (("H", H), ("grad_H", grad_H), ("S", S)):
        _callable(n, f)
    _callable("hessian", hessian, False)
    dim, y = _state(None, None, y0, False)
    return _core.Problem("poisson", dim, _real("t0", t0), y, H, grad_H, S, hessian)


def _rotation(name, R):
    a = np.asarray(R)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name}: expected real numbers, got dtype {a.dtype}")
    if a.shape != (3, 3):
        raise ValueError(f"{name}: expected a 3x3 rotation matrix, got shape {a.shape}")
    a = np.ascontiguousarray(a, dtype=np.float64)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: values must be finite")
    defect = np.abs(a.T @ a - np.eye(3)).max()
    if defect > 1e-10 or np.linalg.det(a) < 0:
        raise ValueError(f"{name}: not a rotation (|R^T R - I| = {defect:.3g}, "
                         f"det = {np.linalg.det(a):.6g})")
    return a


def rigid_body(inertia, Pi0, R0=None, V=None, grad_V=None, mass=None, x0=None, p0=None,
               t0=0.0):
    """A rigid body on SO(3) (or SO(3) × R³ with mass, x0, p0): inertia as the principal
    moments (3,) or the symmetric body inertia tensor (3, 3); Pi0 the body angular momentum,
    R0 the attitude (body to space, default the identity). V(R) -> float and grad_V(R) -> (3,)
    the gradient in the body frame (d/dε V(R exp(ε η̂)) = grad_V(R)·η, minus the torque); with
    a position, V(R, x) and grad_V(R, x) -> (6,): the body gradient, then ∂V/∂x. Neither V nor
    grad_V: a free body. R arrives as a read-only 3x3 array. For the Lie group rows (lgvi,
    rattle-so3, ...)."""
    J = np.asarray(inertia, dtype=np.float64)
    if J.shape == (3,):
        J = np.diag(J)
    if J.shape != (3, 3):
        raise ValueError(f"inertia: expected 3 principal moments or a 3x3 tensor, got shape "
                         f"{J.shape}")
    if not np.all(np.isfinite(J)) or np.abs(J - J.T).max() > 0:
        raise ValueError("inertia: must be finite and symmetric")
    if np.linalg.eigvalsh(J).min() <= 0:
        raise ValueError("inertia: must be positive definite")
    _callable("V", V, False)
    _callable("grad_V", grad_V, False)
    R = np.eye(3) if R0 is None else _rotation("R0", R0)
    Pi = _vector("Pi0", Pi0, 3)
    if mass is None:
        if x0 is not None or p0 is not None:
            raise ValueError("x0 and p0 need a mass (a body with a position)")
        y = np.concatenate([R.ravel(), Pi])
        return _core.Problem("rigid-body", 3, _real("t0", t0), y, V, grad_V,
                             inertia=J.ravel(), mass=0.0)
    mass = _real("mass", mass, positive=True)
    x = _vector("x0", np.zeros(3) if x0 is None else x0, 3)
    p = _vector("p0", np.zeros(3) if p0 is None else p0, 3)
    y = np.concatenate([R.ravel(), x, Pi, p])
    return _core.Problem("rigid-body", 6, _real("t0", t0), y, V, grad_V, inertia=J.ravel(),
                         mass=mass)


def nbody(masses, positions, velocities=None, momenta=None, G=1.0, central=True, eps=0.0):
    """N bodies in 3-D under Newtonian gravity from arrays: masses (n,), positions (n, 3),
    velocities or momenta (n, 3) (barycentric or any inertial frame, used as given). With
    central=True (the default) body 0 is the central body of a planetary system (heavier
    than all others together, no softening): the near-integrable rows (wh-jacobi,
    saba-n-jacobi, sabac-n-jacobi, ...) integrate it, and so do all separable rows. The
    library's built-in "n-body" problem is set up from these arrays (through its file of
    bodies, written with 17 digits: the values are exact); the state is (q, p) with q body by
    body (x1 y1 z1 x2 ...) and p = m v."""
    m = _vector("masses", masses)
    n = m.shape[0]
    if n < 1:
        raise ValueError("masses: need at least one body")
    if np.any(m <= 0):
        raise ValueError(f"masses: must be positive, body {int(np.argmin(m))} has {m.min()}")
    x = np.asarray(positions, dtype=np.float64)
    if x.shape != (n, 3):
        raise ValueError(f"positions: expected shape ({n}, 3), got {x.shape}")
    if (velocities is None) == (momenta is None):
        raise ValueError("give velocities or momenta (one of them)")
    if velocities is not None:
        v = np.asarray(velocities, dtype=np.float64)
        vname = "velocities"
    else:
        v = np.asarray(momenta, dtype=np.float64) / m[:, None]
        vname = "momenta"
    if v.shape != (n, 3):
        raise ValueError(f"{vname}: expected shape ({n}, 3), got {v.shape}")
    for name, a in (("positions", x), (vname, v)):
        bad = np.argwhere(~np.isfinite(a))
        if bad.size:
            raise ValueError(f"{name}: body {bad[0][0]} component {bad[0][1]} is not finite")
    fd, path = tempfile.mkstemp(prefix="geomint-bodies-", suffix=".txt")
    try:
        with os.fdopen(fd, "w") as f:
            for i in range(n):
                f.write(" ".join(repr(float(a)) for a in (m[i], *x[i], *v[i])) + "\n")
        return problem("n-body", set={"file": path, "central": 1.0 if central else 0.0,
                                      "G": _real("G", G, positive=True),
                                      "eps": _real("eps", eps)})
    finally:
        os.unlink(path)


# ---- results -------------------------------------------------------------------------------

class Result:
    """A run: t (n_out,), y (n_out, state_size) and, for states (q, p), the views q and p;
    R (n_out, 3, 3) for rigid bodies; stats (steps, force_evals, ...); the final time and
    state; energy() and rel_energy_error() computed by the library's energy."""

    def __init__(self, problem, method, t, y, stats):
        self.problem, self.method, self.t, self.y, self.stats = problem, method, t, y, stats
        d = problem.dim
        if problem.kind == "rigid-body":
            self.R = y[:, :9].reshape(-1, 3, 3)
            self.Pi = y[:, 9 + (3 if d == 6 else 0):][:, :3]
        if problem.has_momenta:
            self.q, self.p = y[:, :d], y[:, d:]

    @property
    def t_final(self):
        return float(self.t[-1])

    @property
    def y_final(self):
        return self.y[-1]

    def energy(self):
        """Energy at every output state (NaN array for problems without one)."""
        energy = self.problem.energy
        values = [energy(row) for row in self.y]
        return np.array([np.nan if v is None else v for v in values])

    def rel_energy_error(self):
        """|H - H0| / |H0| at every output state (|H - H0| when H0 = 0)."""
        e = self.energy()
        h0 = e[0]
        return np.abs(e - h0) / (abs(h0) if h0 != 0 else 1.0)

    def __repr__(self):
        return (f"Result({self.method}, {len(self.t)} outputs, t = {self.t[0]:g} .. "
                f"{self.t[-1]:.10g}, {self.stats['force_evals']} force evaluations)")


class Integrator:
    """An integrator of one method for one problem (built-in or from Python callables).

    every: record (and call observer(t, y)) every `every` steps, plus the first and last
    state of each run. run(steps, dt) and integrate(t_end, dt) return a Result of that call.
    state is a read-only view of the library's state array (valid until the next step).
    progress: True (a bar on stderr when it is a terminal) or a callable progress(fraction,
    t), called every progress_every steps and at the start and end of each run (observing
    never changes what a run computes)."""

    def __init__(self, problem, method="verlet", basic=None, solver=None, compensated=False,
                 every=1, observer=None, record=True, progress=None, progress_every=1000):
        if isinstance(problem, str):
            problem = globals()["problem"](problem)
        if not isinstance(problem, Problem):
            raise TypeError("problem: expected a name or a geomint problem")
        if not isinstance(method, str):
            raise TypeError(f"method: expected a str, got {type(method).__name__}")
        every = _count("every", every)
        if every < 1:
            raise ValueError("every: must be >= 1")
        _callable("observer", observer, False)
        progress_every = _count("progress_every", progress_every)
        if progress_every < 1:
            raise ValueError("progress_every: must be >= 1")
        progress = _resolve_progress(progress, f"{method}")
        self.problem, self.method = problem, method
        self._it = _core.Integrator(method, problem, basic, solver, bool(compensated), every,
                                    observer, bool(record), progress, progress_every)

    def set_state(self, t, y):
        """Set time and state (copied)."""
        self._it.set_state(_real("t", t), _vector("y", y, self.problem.state_size))

    def run(self, steps, dt):
        """`steps` steps of size dt (negative: backwards)."""
        steps, dt = _count("steps", steps), _real("dt", dt)
        if dt == 0:
            raise ValueError("dt: must be non-zero")
        t, y = self._it.run(steps, dt)
        return Result(self.problem, self.method, t, y, self._it.stats)

    def integrate(self, t_end, dt):
        """Equal steps of at most dt ending exactly at t_end."""
        t_end, dt = _real("t_end", t_end), _real("dt", dt, positive=True)
        if t_end <= self._it.time:
            raise ValueError(f"t_end: must be after the current time {self._it.time:g}, "
                             f"got {t_end:g}")
        t, y = self._it.integrate(t_end, dt)
        return Result(self.problem, self.method, t, y, self._it.stats)

    def save(self, path):
        """Write a checkpoint (the library's binary format) to path."""
        self._it.save(str(path))

    def load(self, path):
        """Load a checkpoint saved from the same method and problem."""
        self._it.load(str(path))

    def resume(self):
        """Continue the run of a loaded checkpoint; bitwise as without interruption."""
        t, y = self._it.resume()
        return Result(self.problem, self.method, t, y, self._it.stats)

    @property
    def time(self):
        return self._it.time

    @property
    def state(self):
        return self._it.state

    @property
    def stats(self):
        return self._it.stats

    @property
    def solver(self):
        return self._it.solver


def run(problem, method="verlet", dt=0.01, steps=None, t_end=None, set=None, every=1,
        basic=None, solver=None, compensated=False, observer=None, y0=None, t0=None,
        progress=None):
    """Integrate a problem (a built-in name, with parameters in `set`, or a problem object)
    from its initial state (or y0 at t0) with `steps` steps of dt, or up to `t_end` (default
    10 when neither is given, as `geomint run`). Returns a Result with t, q, p (or y) of
    every `every`-th step, the first and the last, and the statistics. progress=True draws a
    bar on stderr (when it is a terminal), a callable gets progress(fraction, t), about 200
    times per run."""
    if steps is not None and t_end is not None:
        raise ValueError("give steps or t_end, not both")
    if isinstance(problem, str):
        problem = globals()["problem"](problem, set)
    elif set is not None:
        raise ValueError("set: only for built-in problems given by name")
    start = problem.t0 if t0 is None else _real("t0", t0)
    if steps is not None:
        planned = _count("steps", steps)
    else:
        span = (10.0 if t_end is None else _real("t_end", t_end)) - start
        planned = int(math.ceil(span / _real("dt", dt, positive=True))) if span > 0 else 1
    it = Integrator(problem, method, basic, solver, compensated, every, observer,
                    progress=progress, progress_every=max(1, planned // 200))
    if y0 is not None or t0 is not None:
        it.set_state(problem.t0 if t0 is None else t0,
                     problem.y0 if y0 is None else y0)
    if steps is not None:
        return it.run(steps, dt)
    return it.integrate(10.0 if t_end is None else t_end, dt)


def order(method, problem, t_end=1.0, set=None, basic=None, solver=None):
    """Measured order of a method on a problem (levels chosen inside the declared order's
    asymptotic window, as `geomint order`): dict with order, declared, dts, errors, outcome."""
    if isinstance(problem, str):
        problem = globals()["problem"](problem, set)
    return _core.order(method, problem, _real("t_end", t_end, positive=True), basic, solver)


def _final_error(problem, y_final, t_end, reference):
    if reference is not None:
        return float(np.max(np.abs(y_final - reference)))
    exact = problem.exact(t_end)
    if exact is None:
        raise ValueError("work_precision: the problem has no exact solution; give reference= "
                         "(the state at t_end) or reference_method=")
    return float(np.max(np.abs(y_final - exact)))


def work_precision(methods, problem, dts, t_end, set=None, reference=None,
                   reference_method=None, reference_dt=None, error="state"):
    """Cost against error of methods over steps dts up to t_end. error="state": max |y - y_ref|
    at t_end against the exact solution (problems that have one), the array `reference`, or a
    run of `reference_method` with `reference_dt`; error="energy": the largest relative energy
    error over the run (recorded every step). Returns {method: {"dt", "steps", "force_evals",
    "seconds", "error"}} of arrays (CPU seconds of the runs), ready for
    geomint.plot.work_precision(..., cost="force_evals")."""
    if isinstance(methods, str):
        methods = [methods]
    if isinstance(problem, str):
        problem = globals()["problem"](problem, set)
    t_end = _real("t_end", t_end)
    if error not in ("state", "energy"):
        raise ValueError(f"error: 'state' or 'energy', got {error!r}")
    if error == "state" and reference is None and reference_method is not None:
        ref = Integrator(problem, reference_method, every=2 ** 62)
        ref.integrate(t_end, _real("reference_dt", reference_dt, positive=True))
        reference = np.array(ref.state)
    elif reference is not None:
        reference = _vector("reference", reference, problem.state_size)
    out = {}
    for m in methods:
        rows = {k: [] for k in ("dt", "steps", "force_evals", "seconds", "error")}
        for dt in dts:
            dt = _real("dt", dt, positive=True)
            it = Integrator(problem, m, every=1 if error == "energy" else 2 ** 62)
            c0 = time.process_time()
            r = it.integrate(t_end, dt)
            seconds = time.process_time() - c0
            if error == "energy":
                err = float(r.rel_energy_error().max())
            else:
                err = _final_error(problem, np.asarray(it.state), t_end, reference)
            st = it.stats
            for k, v in (("dt", dt), ("steps", st["steps"]), ("force_evals", st["force_evals"]),
                         ("seconds", seconds), ("error", err)):
                rows[k].append(v)
        out[m] = {k: np.array(v) for k, v in rows.items()}
    return out
