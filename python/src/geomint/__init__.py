"""geomint: geometric numerical integration (a thin package over the C library libgeomint).

    >>> import geomint
    >>> r = geomint.run("kepler", method="verlet", dt=0.01, steps=1000)
    >>> r.q.shape
    (1001, 2)
"""
from ._core import Error
from .ode import (Problem, Integrator, Result, methods, method, problems, problem, run, order,
                  separable, hamiltonian, lagrangian, first_order, poisson, rigid_body, nbody,
                  work_precision)

__all__ = ["Error", "Problem", "Integrator", "Result", "methods", "method", "problems",
           "problem", "run", "order", "separable", "hamiltonian", "lagrangian", "first_order",
           "poisson", "rigid_body", "nbody", "work_precision"]
from . import dec, yee, fields, pde, progress  # noqa: E402  (geomint.plot: on demand, matplotlib)
