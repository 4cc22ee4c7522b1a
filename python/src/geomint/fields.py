"""Fields beyond the Yee grid: Maxwell on simplicial meshes (the DEC leapfrog of
Bossavit–Kettunen and the asynchronous variational integrator, docs/maxwell-mesh.md) and
harminv, the resonances of a sampled signal (used for probe signals of both solvers)."""
import math

import numpy as np

from . import _core
from .dec import Complex
from .progress import advance_in_chunks, resolve as _resolve_progress


def harminv(signal, dt, f_min, f_max, n_basis=0, max_modes=100):
    """Resonances of a signal sampled every dt (real, or complex as a complex array) with
    frequencies in [f_min, f_max] (Mandelshtam & Taylor filter diagonalization, the harminv
    library): a dict of arrays frequency, decay, q, amplitude, phase, error, ascending in
    frequency. Every mode in the band is returned: filter on error and amplitude yourself."""
    a = np.asarray(signal)
    if a.ndim != 1:
        raise ValueError(f"signal: expected a 1-D array, got shape {a.shape}")
    if a.dtype.kind not in "fiuc":
        raise TypeError(f"signal: expected numbers, got dtype {a.dtype}")
    if not np.all(np.isfinite(a)):
        raise ValueError("signal: values must be finite")
    for name, v in (("dt", dt), ("f_min", f_min), ("f_max", f_max)):
        if not math.isfinite(float(v)):
            raise ValueError(f"{name}: must be finite")
    if a.dtype.kind == "c":
        re, im = np.ascontiguousarray(a.real, float), np.ascontiguousarray(a.imag, float)
    else:
        re, im = np.ascontiguousarray(a, float), None
    return _core.harminv(re, im, float(dt), float(f_min), float(f_max), int(n_basis),
                         int(max_modes))


class MeshMaxwell:
    """Maxwell's equations on a 2-D triangle mesh (TE: E on edges, B = Bz on triangles) or a
    3-D tetrahedral mesh, with PEC walls, ε and μ per top simplex (default vacuum), units
    ε0 = μ0 = c = 1. scheme "leapfrog" (the DEC leapfrog, diagonal circumcentric stars: needs a
    well-centred mesh, or star="whitney" for any mesh) or "avi" (asynchronous variational
    integrator, per-face steps avi_fraction × the local limit). dt <= 0: courant × the CFL
    limit. E is a read-only view of the solver's edge values; B a copy at the current time."""

    def __init__(self, cx, epsilon=None, mu=None, scheme="leapfrog", star="diagonal", dt=0.0,
                 courant=0.9, avi_fraction=0.1, allow_negative_stars=False):
        if not isinstance(cx, Complex):
            raise TypeError("cx: expected a geomint.dec.Complex")
        if scheme not in ("leapfrog", "avi"):
            raise ValueError(f"scheme: 'leapfrog' or 'avi', got {scheme!r}")
        if star not in ("diagonal", "whitney"):
            raise ValueError(f"star: 'diagonal' or 'whitney', got {star!r}")
        self.complex = cx
        self._m = _core.MeshMaxwell(cx._cx, epsilon, mu, scheme == "avi", star == "whitney",
                                    float(dt), float(courant), float(avi_fraction),
                                    bool(allow_negative_stars))

    def set_fields(self, E, B=None):
        """Initial E (one value per edge: ∫_e E·dl, at t0 − dt/2) and B (per face: the flux);
        copied, E on boundary edges set to 0. Only before the first advance."""
        self._m.set_fields(np.asarray(E, dtype=np.float64),
                           None if B is None else np.asarray(B, dtype=np.float64))

    def advance(self, steps, progress=None):
        """`steps` leapfrog steps; progress as in geomint.run."""
        if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 0:
            raise ValueError(f"steps: expected an integer >= 0, got {steps!r}")
        advance_in_chunks(self._m.advance, int(steps), _resolve_progress(progress, "maxwell"),
                          lambda: self._m.time)

    def advance_to(self, t):
        """Leapfrog: to the last step with t_n <= t; AVI: every face event up to t."""
        self._m.advance_to(float(t))

    def add_probe(self, component, x, capacity=100000):
        """Record component ("Ex", "Ey", "Hz", ...: the Whitney interpolant) at point x after
        every step; returns the probe's id for probe(id)."""
        x = tuple(float(v) for v in x) + (0.0,) * (3 - len(x))
        return self._m.add_probe(component, x, int(capacity))

    def probe(self, probe_id):
        """(t, values) recorded by a probe."""
        return self._m.probe(int(probe_id))

    def energy(self):
        """Electric ½Eᵀ⋆εE, magnetic ½Bᵀ⋆νB, plain (their sum) and the leapfrog energy (exactly
        conserved by the leapfrog without sources)."""
        return self._m.energy()

    def div_b(self):
        """max |d B| over the top simplices (0 in 2-D)."""
        return self._m.div_b()

    def gauss(self):
        """div D − ρ per vertex (0 on the boundary)."""
        return self._m.gauss()

    @property
    def E(self):
        """E on the edges: a read-only view of the solver's array (valid until the next advance)."""
        return self._m.E

    @property
    def B(self):
        """B on the faces at the current time (a copy; the AVI synchronises it)."""
        return self._m.B

    @property
    def dt(self):
        """The leapfrog's time step."""
        return self._m.dt

    @property
    def time(self):
        """The time reached."""
        return self._m.time

    @property
    def step(self):
        """Steps (AVI: face events) done."""
        return self._m.step

    @property
    def cfl_limit(self):
        """The leapfrog's CFL limit 2/sqrt(λ_max) of this mesh and these materials."""
        return self._m.cfl_limit
