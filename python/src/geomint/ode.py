"""ODEs: the method table, built-in and user problems, the integrator and `run`.

Everything numerical happens in libgeomint; this module checks arguments (shapes, dtypes,
NaN) before they reach C and shapes the results as NumPy arrays.
"""
import math
import numbers

import numpy as np

from . import _core
from ._core import Error

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
    state is a read-only view of the library's state array (valid until the next step)."""

    def __init__(self, problem, method="verlet", basic=None, solver=None, compensated=False,
                 every=1, observer=None, record=True):
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
        self.problem, self.method = problem, method
        self._it = _core.Integrator(method, problem, basic, solver, bool(compensated), every,
                                    observer, bool(record))

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
        basic=None, solver=None, compensated=False, observer=None, y0=None, t0=None):
    """Integrate a problem (a built-in name, with parameters in `set`, or a problem object)
    from its initial state (or y0 at t0) with `steps` steps of dt, or up to `t_end` (default
    10 when neither is given, as `geomint run`). Returns a Result with t, q, p (or y) of
    every `every`-th step, the first and the last, and the statistics."""
    if steps is not None and t_end is not None:
        raise ValueError("give steps or t_end, not both")
    if isinstance(problem, str):
        problem = globals()["problem"](problem, set)
    elif set is not None:
        raise ValueError("set: only for built-in problems given by name")
    it = Integrator(problem, method, basic, solver, compensated, every, observer)
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
