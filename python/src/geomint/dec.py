"""Discrete exterior calculus: simplicial complexes from a Gmsh/OFF file or from arrays, the
operators d, ⋆, δ and the Hodge Laplacians as scipy.sparse.csr_matrix, mesh quality and a
Poisson solve. The matrices are assembled by libgeomint (copied into SciPy's arrays)."""
import os

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from . import _core


def _csr(parts):
    data, indices, indptr, shape = parts
    return sp.csr_matrix((data, indices, indptr), shape=shape)


class Complex:
    """A simplicial complex with its circumcentric geometry.

    Complex.from_file("mesh.msh") reads Gmsh (2.2 or 4.1 ASCII) or OFF; Complex.from_arrays(
    vertices (n, N) float, simplices (m, dim+1) int) builds one from arrays (copied)."""

    def __init__(self, core):
        self._cx = core

    @classmethod
    def from_file(cls, path):
        path = os.fspath(path)
        if not os.path.exists(path):
            raise FileNotFoundError(f"mesh file {path!r} does not exist")
        return cls(_core.Complex(path=path))

    @classmethod
    def from_arrays(cls, vertices, simplices):
        v = np.asarray(vertices)
        s = np.asarray(simplices)
        if v.dtype.kind not in "fiu":
            raise TypeError(f"vertices: expected real numbers, got dtype {v.dtype}")
        if v.ndim != 2 or not 1 <= v.shape[1] <= 3:
            raise ValueError(f"vertices: expected shape (n, N) with N in 1..3, got {v.shape}")
        if not np.all(np.isfinite(v)):
            raise ValueError("vertices: coordinates must be finite")
        if s.dtype.kind not in "iu":
            raise TypeError(f"simplices: expected integers, got dtype {s.dtype}")
        if s.ndim != 2 or not 2 <= s.shape[1] <= 4:
            raise ValueError(f"simplices: expected shape (m, dim+1) with dim in 1..3, got {s.shape}")
        if s.size and (s.min() < 0 or s.max() >= v.shape[0]):
            raise ValueError(f"simplices: vertex indices must be in 0..{v.shape[0] - 1}")
        return cls(_core.Complex(vertices=np.ascontiguousarray(v, dtype=np.float64),
                                 simplices=np.ascontiguousarray(s, dtype=np.uint64)))

    PATTERNS = {"right": 0, "left": 1, "alternate": 2, "acute": 3}

    @classmethod
    def rectangle(cls, x0, x1, y0, y1, nx, ny, pattern="acute"):
        """The triangulated rectangle [x0, x1] × [y0, y1] with nx × ny cells; pattern "right",
        "left", "alternate" (diagonals) or "acute" (rows shifted by half a cell: well-centred
        inside, as mesh Maxwell's diagonal stars need)."""
        if pattern not in cls.PATTERNS:
            raise ValueError(f"pattern: one of {', '.join(cls.PATTERNS)}, got {pattern!r}")
        return cls(_core.mesh_rectangle(float(x0), float(x1), float(y0), float(y1), int(nx),
                                        int(ny), cls.PATTERNS[pattern]))

    @classmethod
    def box(cls, lo, hi, n, pattern="kuhn"):
        """The tetrahedralized box [lo, hi] with n = (nx, ny, nz) cubes, 6 ("kuhn") or 5
        ("five") tetrahedra each."""
        if pattern not in ("kuhn", "five"):
            raise ValueError(f"pattern: 'kuhn' or 'five', got {pattern!r}")
        nx, ny, nz = (int(v) for v in n)
        return cls(_core.mesh_box(tuple(map(float, lo)), tuple(map(float, hi)), nx, ny, nz,
                                  0 if pattern == "kuhn" else 1))

    @property
    def dim(self):
        """Dimension of the top simplices."""
        return self._cx.dim

    @property
    def vertices(self):
        """Vertex coordinates, (n, N): a read-only view of the library's array."""
        return self._cx.vertices

    def count(self, k):
        """Number of k-simplices."""
        return self._cx.count(k)

    def simplices(self, k):
        """k-simplices as rows of vertex indices (library orientation)."""
        return self._cx.simplices(k)

    def boundary(self, k):
        """Boolean mask of the k-simplices on the boundary."""
        return self._cx.boundary_mask(k)

    def d(self, k):
        """Exterior derivative d_k: k-cochains -> (k+1)-cochains (csr_matrix of ±1)."""
        return _csr(self._cx.d(k))

    def star(self, k):
        """Diagonal Hodge star ⋆_k (|dual| / |primal|) as a csr_matrix."""
        return sp.diags(self._cx.star(k), format="csr")

    def codifferential(self, k):
        """δ_k = ⋆_{k-1}^{-1} d_{k-1}^T ⋆_k: k-cochains -> (k-1)-cochains."""
        return _csr(self._cx.codifferential(k))

    def laplacian(self, k):
        """Hodge–de Rham Laplacian Δ_k = d δ + δ d (Δ_0 ≈ -∇²)."""
        return _csr(self._cx.laplacian(k))

    def volumes(self, k, dual=False):
        """Primal (or dual) volumes of the k-simplices."""
        return self._cx.volumes(k, bool(dual))

    def wedge(self, k, alpha, l, beta):
        """Primal–primal wedge α∧β of a k-cochain and an l-cochain (barycentric; Leibniz
        holds exactly): count(k + l) values."""
        return self._cx.wedge(k, np.asarray(alpha, dtype=np.float64), l,
                              np.asarray(beta, dtype=np.float64))

    def flat(self, X):
        """♭ of a vector field given per top simplex (shape (count(dim), N)): a 1-cochain."""
        return self._cx.flat(np.asarray(X, dtype=np.float64))

    def sharp(self, alpha):
        """♯ of a 1-cochain: a vector per vertex, shape (count(0), N)."""
        return self._cx.sharp(np.asarray(alpha, dtype=np.float64))

    def quality(self):
        """The mesh quality report (counts, Euler characteristic, degenerate, inverted and
        not-well-centred cells, ⋆ ranges, volumes and edge lengths)."""
        return self._cx.quality()

    def poisson_check(self):
        """The library's manufactured-solution Poisson solve: (report, u at the vertices)."""
        return self._cx.poisson_check()


def poisson(cx, f, g):
    """Solve -Δu = f with u = g on the boundary vertices, in the DEC form
    d0ᵀ ⋆1 d0 u = ⋆0 f on the interior vertices, with SciPy's sparse solver.
    f, g: arrays of one value per vertex (g is read on boundary vertices only)."""
    n = cx.count(0)
    f = np.asarray(f, dtype=np.float64)
    g = np.asarray(g, dtype=np.float64)
    for name, a in (("f", f), ("g", g)):
        if a.shape != (n,):
            raise ValueError(f"{name}: expected {n} values (one per vertex), got shape {a.shape}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name}: values must be finite")
    d0 = cx.d(0)
    stiffness = (d0.T @ cx.star(1) @ d0).tocsr()
    rhs = cx.star(0) @ f
    bnd = cx.boundary(0)
    inner = ~bnd
    u = np.where(bnd, g, 0.0)
    rhs = rhs - stiffness @ u
    u[inner] = spla.spsolve(stiffness[inner][:, inner].tocsc(), rhs[inner])
    return u
