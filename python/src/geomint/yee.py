"""The Yee FDTD solver from a scene (the schema of the JSON scene files, docs/maxwell.md),
read by the library (gm_yee_scene_parse), with fields as NumPy views of its arrays."""
import json
import os

import numpy as np

from . import _core
from .progress import advance_in_chunks, resolve as _resolve_progress


class Scene:
    """Scene(dict or path): the solver of a scene. fields are read-only views of the
    library's arrays (valid until the next advance), indexed [k, j, i] (x fastest)."""

    def __init__(self, scene, name="scene"):
        if isinstance(scene, (str, os.PathLike)):
            path = os.fspath(scene)
            with open(path) as f:
                text = f.read()
            name = path
        elif isinstance(scene, dict):
            try:
                text = json.dumps(scene, allow_nan=False)
            except (TypeError, ValueError) as e:
                raise ValueError(f"scene: not representable as JSON: {e}") from None
        else:
            raise TypeError("scene: expected a dict or a path to a JSON file")
        self._y = _core.Yee(text, str(name))

    def advance(self, steps, progress=None):
        """Advance `steps` time steps. progress=True: a bar on stderr (when a terminal), or a
        callable progress(fraction, t); the run is then advanced in about 200 pieces, which
        computes the same fields bit for bit."""
        if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 0:
            raise ValueError(f"steps: expected an integer >= 0, got {steps!r}")
        advance_in_chunks(self._y.advance, int(steps), _resolve_progress(progress, "yee"),
                          lambda: self._y.time)

    def advance_to(self, t):
        """Advance to time t (H at n dt >= t)."""
        self._y.advance_to(float(t))

    def run(self, progress=None):
        """Advance as many steps as the scene's "run" asks for (progress as in advance)."""
        self.advance(int(self._y.run_steps()), progress)

    def field(self, component, ghosts=False):
        """Component ("Ex".."Hz") on its own locations, shape (nz, ny, nx) of that component,
        a read-only view (ghosts=True: the whole array with its ghost layers)."""
        a, off, cnt = self._y.field(component)
        if ghosts:
            return a
        return a[off[0]:off[0] + cnt[0], off[1]:off[1] + cnt[1], off[2]:off[2] + cnt[2]]

    def probes(self):
        """{name: (t, values)} of every probe of the scene."""
        return self._y.probes()

    def harminv(self, probe, f_min, f_max, n_basis=0, max_modes=100, t_min=0.0):
        """Resonances of a probe's signal (from time t_min on, e.g. after the source has
        died down) in [f_min, f_max]: geomint.fields.harminv of the samples."""
        from .fields import harminv
        probes = self.probes()
        if probe not in probes:
            raise KeyError(f"probe {probe!r}: the scene has {sorted(probes)}")
        t, v = probes[probe]
        keep = t >= t_min
        t, v = t[keep], v[keep]
        if t.size < 8:
            raise ValueError(f"probe {probe!r}: {t.size} samples after t = {t_min}, harminv "
                             "needs at least 8")
        return harminv(v, float(t[1] - t[0]), f_min, f_max, n_basis, max_modes)

    def energy(self):
        """Electric, magnetic, plain and leapfrog energies."""
        return self._y.energy()

    def fluxes(self):
        """{name: Poynting flux} through the scene's flux planes now."""
        return self._y.fluxes()

    @property
    def time(self):
        return self._y.time

    @property
    def dt(self):
        return self._y.dt

    @property
    def step(self):
        return self._y.step

    @property
    def grid(self):
        return self._y.grid
