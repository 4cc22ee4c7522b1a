"""geomint: geometric numerical integration (a thin package over the C library libgeomint).

    >>> import geomint
    >>> r = geomint.run("kepler", method="verlet", dt=0.01, steps=1000)
    >>> r.q.shape
    (1001, 2)
"""
from ._core import Error
from .ode import (Problem, Integrator, Result, methods, method, problems, problem, run, order,
                  separable, hamiltonian, lagrangian, first_order)

__all__ = ["Error", "Problem", "Integrator", "Result", "methods", "method", "problems",
           "problem", "run", "order", "separable", "hamiltonian", "lagrangian", "first_order"]
from . import dec, yee  # noqa: E402  (geomint.plot is imported on demand: matplotlib)
