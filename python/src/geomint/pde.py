"""Multisymplectic schemes for Hamiltonian PDEs in 1+1 dimensions, 𝕎 s_t + 𝕂 s_x = ∇S(s)
(Bridges & Reich 2001; docs/pde.md): the built-in equations sine-gordon, nls and kdv on a
periodic (or Dirichlet) grid with the schemes of the library's table (preissmann, euler-box,
lf, ec, ms, zk, box-sdirk2, gauss-prk)."""
import numpy as np

from . import _core
from .progress import advance_in_chunks, resolve as _resolve_progress

EQUATIONS = {"sine-gordon": 3, "nls": 4, "kdv": 4}   # components per point


def schemes():
    """The scheme table: dicts with name, order_t, order_x, multisymplectic,
    energy_conserving, explicit, scalar (wave equations only), law, reference."""
    return _core.pde_schemes()


def points(scheme, n, h, x0=0.0):
    """x of every state point (x0 + i h; for gauss-prk the two Gauss points of each cell):
    sample the initial data there."""
    return _core.pde_point_x(scheme, int(n), float(h), float(x0))


class Pde:
    """A run of one scheme on one equation. s0: the initial state, shape (n, d) with d the
    equation's components (sine-gordon (u, v = u_t, w = u_x), nls (p, q, p_x, q_x), kdv
    (φ, u, u_x, w)); n points with spacing h from x0; twist: s_{i+n} = s_i + twist (a kink's
    2π in u). state is a read-only (n, d) view valid until the next advance."""

    def __init__(self, equation, scheme, s0, h, dt, x0=0.0, twist=None, newton_tol=0.0,
                 newton_max_iter=0, dirichlet_left=0, dirichlet_right=0,
                 track_variations=False):
        if equation not in EQUATIONS:
            raise ValueError(f"equation: one of {', '.join(EQUATIONS)}, got {equation!r}")
        d = EQUATIONS[equation]
        s = np.asarray(s0)
        if s.dtype.kind not in "fiu":
            raise TypeError(f"s0: expected real numbers, got dtype {s.dtype}")
        if s.ndim != 2 or s.shape[1] != d:
            raise ValueError(f"s0: expected shape (n, {d}) for {equation}, got {s.shape}")
        if not np.all(np.isfinite(s)):
            bad = np.argwhere(~np.isfinite(s))[0]
            raise ValueError(f"s0: point {bad[0]} component {bad[1]} is not finite")
        tw = np.zeros(d) if twist is None else np.asarray(twist, dtype=np.float64)
        self.equation, self.scheme = equation, scheme
        self._p = _core.Pde(equation, scheme, s.shape[0], float(h), float(x0), tw, float(dt),
                            np.ascontiguousarray(s, dtype=np.float64), float(newton_tol),
                            int(newton_max_iter), int(dirichlet_left), int(dirichlet_right),
                            bool(track_variations))

    def advance(self, steps, progress=None):
        """`steps` time steps; progress as in geomint.run."""
        if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 0:
            raise ValueError(f"steps: expected an integer >= 0, got {steps!r}")
        advance_in_chunks(self._p.advance, int(steps),
                          _resolve_progress(progress, self.scheme), lambda: self._p.time)

    def invariants(self):
        """Global monitors: energy and momentum (the densities of the local laws), norm (NLS),
        mass (KdV), cell-averaged energy and momentum, the multisymplectic residual (NaN unless
        track_variations)."""
        return self._p.invariants()

    @property
    def state(self):
        """The state (n, d): a read-only view of the solver's array, valid until the next advance."""
        return self._p.state

    @property
    def time(self):
        """The time reached."""
        return self._p.time

    @property
    def steps(self):
        """Steps done."""
        return self._p.steps

    @property
    def stats(self):
        """Newton iterations, factorizations, gradient evaluations of the run so far."""
        return self._p.stats
