"""Near-integrable N-body from arrays, Poisson systems and rigid bodies from callables,
work–precision and progress from Python: against the library's built-in problems."""
import io
import math

import numpy as np
import pytest

import geomint
from geomint import progress as gprogress

# the outer solar system of src/problems/outer_solar_system.c (Hairer, Lubich & Wanner, GNI
# §I.2.4): the same numbers given as arrays
MASSES = np.array([1.00000597682, 0.000954786104043, 0.000285583733151, 0.0000437273164546,
                   0.0000517759138449, 1.0 / 1.3e8])
POSITIONS = np.array([[0.0, 0.0, 0.0], [-3.5023653, -3.8169847, -1.5507963],
                      [9.0755314, -3.0458353, -1.6483708], [8.3101420, -16.2901086, -7.2521278],
                      [11.4707666, -25.7294829, -10.8169456],
                      [-15.5387357, -25.2225594, -3.1902382]])
VELOCITIES = np.array([[0.0, 0.0, 0.0], [0.00565429, -0.00412490, -0.00190589],
                       [0.00168318, 0.00483525, 0.00192462], [0.00354178, 0.00137102, 0.00055029],
                       [0.00288930, 0.00114527, 0.00039677],
                       [0.00276725, -0.00170702, -0.00136504]])
G_SUN = 2.95912208286e-4


def test_nbody_from_arrays_equals_builtin_bitwise():
    pb = geomint.nbody(MASSES, POSITIONS, VELOCITIES, G=G_SUN)
    assert pb.kind == "separable" and pb.dim == 18
    np.testing.assert_array_equal(pb.y0, geomint.problem("outer-solar-system").y0)
    errors = {}
    for method in ("wh-c5", "sabac-4-jacobi", "saba-2-jacobi", "blanes-moan-6"):
        a = geomint.run(pb, method=method, dt=100.0, steps=500, every=100)
        b = geomint.run("outer-solar-system", method=method, dt=100.0, steps=500, every=100)
        np.testing.assert_array_equal(a.y, b.y)
        assert a.stats == b.stats
        errors[method] = a.rel_energy_error().max()
    # 50 000 days at 100 days: measured energy errors sabac-4-jacobi 1.0e-13, blanes-moan-6 5.4e-10
    assert errors["sabac-4-jacobi"] < 5e-13 and errors["blanes-moan-6"] > 1e3 * errors["sabac-4-jacobi"]


def test_nbody_momenta_and_errors():
    p = MASSES[:, None] * VELOCITIES
    pb = geomint.nbody(MASSES, POSITIONS, momenta=p, G=G_SUN)
    np.testing.assert_allclose(pb.y0[18:], p.ravel(), rtol=1e-15, atol=0)
    with pytest.raises(ValueError, match="give velocities or momenta"):
        geomint.nbody(MASSES, POSITIONS)
    with pytest.raises(ValueError, match=r"positions: expected shape \(6, 3\)"):
        geomint.nbody(MASSES, POSITIONS[:5], VELOCITIES)
    with pytest.raises(ValueError, match="masses: must be positive, body 2"):
        geomint.nbody(np.where(np.arange(6) == 2, -1.0, MASSES), POSITIONS, VELOCITIES)
    bad = VELOCITIES.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="velocities: body 3 component 1 is not finite"):
        geomint.nbody(MASSES, POSITIONS, bad)
    # the library's own checks come back with its message
    with pytest.raises(geomint.Error, match="central = 1 needs body 1 heavier than all the "
                       "others together"):
        geomint.nbody([1.0, 2.0], POSITIONS[:2], VELOCITIES[:2])
    with pytest.raises(geomint.Error, match="lines 1 and 2 are at the same place"):
        geomint.nbody([1.0, 1e-3], [[0, 0, 0], [0, 0, 0]], np.zeros((2, 3)))
    # a near-integrable row refuses a problem without a central body
    free = geomint.nbody([1.0, 1.0], [[0, 0, 0], [1, 0, 0]], [[0, 0.5, 0], [0, -0.5, 0]],
                         central=False)
    with pytest.raises(geomint.Error, match="wh"):
        geomint.run(free, method="wh", dt=0.01, steps=10)


def heavy_top_from_callables():
    ht = geomint.problem("heavy-top")
    R0, Pi0 = ht.y0[:9].reshape(3, 3), ht.y0[9:12]
    e3 = np.array([0.0, 0.0, 1.0])
    # V = mgl e3·(R e3) = mgl R[2, 2]; body gradient mgl e3 × Γ with Γ = Rᵀe3 (src/problems/rigid.c)
    return geomint.rigid_body([1.0, 1.0, 0.5], Pi0, R0, V=lambda R: 1.0 * R[2, 2],
                              grad_V=lambda R: 1.0 * np.cross(e3, R[2]))


def test_rigid_body_from_callables_equals_heavy_top():
    top = heavy_top_from_callables()
    assert top.kind == "rigid-body" and top.state_size == 12
    for method in ("lgvi", "rkmk4", "rigid-splitting"):
        a = geomint.run(top, method=method, dt=0.01, steps=300, every=50)
        b = geomint.run("heavy-top", method=method, dt=0.01, steps=300, every=50)
        np.testing.assert_array_equal(a.y, b.y)
    assert a.R.shape == (7, 3, 3)
    assert np.abs(np.einsum("nji,njk->nik", a.R, a.R) - np.eye(3)).max() < 1e-14


def test_free_rigid_body_and_position():
    fb = geomint.rigid_body(np.diag([2.0, 1.0, 2.0 / 3.0]), [1.0, 0.5, 0.3])
    r = geomint.run(fb, method="lgvi", dt=0.05, t_end=20.0)
    # free body: energy and |Π| kept to round-off by lgvi (measured 2.1e-15 and 1.1e-15)
    assert r.rel_energy_error().max() < 2e-14
    assert np.abs(np.linalg.norm(r.Pi, axis=1) - math.sqrt(1.34)).max() < 1e-14
    # a body with a position in a uniform field: V(R, x) = x3, gradient (0, 0, 0; 0, 0, 1)
    body = geomint.rigid_body([1.0, 2.0, 3.0], [0.1, 0.2, 0.3], V=lambda R, x: x[2],
                              grad_V=lambda R, x: np.array([0, 0, 0, 0, 0, 1.0]), mass=2.0,
                              x0=[0, 0, 0], p0=[1.0, 0, 4.0])
    assert body.state_size == 18
    r = geomint.run(body, method="lgvi", dt=0.01, steps=100)
    x, p = r.y[-1, 9:12], r.y[-1, 15:18]
    # free fall: x3 = p3/m t - t²/(2m), exact for the splitting's kicks and drifts
    assert x[2] == pytest.approx(4.0 / 2 * 1.0 - 1.0 / 4, abs=1e-12)
    assert p[2] == pytest.approx(3.0, abs=1e-12) and x[0] == pytest.approx(0.5, abs=1e-14)


def test_rigid_body_errors():
    with pytest.raises(ValueError, match="R0: not a rotation"):
        geomint.rigid_body([1, 2, 3], [0, 0, 1], R0=np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(ValueError, match="inertia: must be positive definite"):
        geomint.rigid_body([1, -2, 3], [0, 0, 1])
    with pytest.raises(ValueError, match="give both V and grad_V"):
        geomint.rigid_body([1, 2, 3], [0, 0, 1], V=lambda R: 0.0)
    with pytest.raises(ValueError, match="Pi0: expected 3 values"):
        geomint.rigid_body([1, 2, 3], [0, 1])
    top = geomint.rigid_body([1, 1, 0.5], [0, 0.3, 2.5], V=lambda R: R[2, 2],
                             grad_V=lambda R: np.zeros(2))
    with pytest.raises(ValueError, match=r"potential gradient \(body frame\) returned 2 values"):
        geomint.run(top, method="lgvi", dt=0.01, steps=3)


def lotka_volterra_callables(hessian=True):
    # src/problems/lotka_volterra.c: H = -(ln u - u + 2 ln v - v), S = uv [[0, 1], [-1, 0]]
    H = lambda y: -(np.log(y[0]) - y[0] + 2 * np.log(y[1]) - y[1])  # noqa: E731
    grad = lambda y: np.array([1 - 1 / y[0], 1 - 2 / y[1]])  # noqa: E731
    S = lambda y: np.array([[0.0, y[0] * y[1]], [-y[0] * y[1], 0.0]])  # noqa: E731
    hess = (lambda y: np.diag([1 / y[0] ** 2, 2 / y[1] ** 2])) if hessian else None
    return geomint.poisson(H, grad, S, [3.0, 3.0], hessian=hess)


def test_poisson_system_from_callables():
    lv = lotka_volterra_callables()
    assert lv.kind == "poisson" and lv.state_size == 2
    a = geomint.run(lv, method="avf", dt=0.1, t_end=20.0)
    b = geomint.run("lotka-volterra", method="avf", dt=0.1, t_end=20.0)
    np.testing.assert_array_equal(a.y, b.y)                   # measured: bitwise
    assert a.stats == b.stats
    for m in ("discrete-gradient-gonzalez", "discrete-gradient-itoh-abe"):
        a = geomint.run(lv, method=m, dt=0.1, t_end=20.0)
        b = geomint.run("lotka-volterra", method=m, dt=0.1, t_end=20.0)
        assert np.abs(a.y - b.y).max() < 1e-11                # measured 1.7e-14, 2.6e-13
        assert a.rel_energy_error().max() < 1e-14             # measured 8e-16, 2e-15
    # without the Hessian: central differences, the same run to round-off (measured 1.6e-13)
    a = geomint.run(lotka_volterra_callables(False), method="avf", dt=0.1, t_end=20.0)
    b = geomint.run("lotka-volterra", method="avf", dt=0.1, t_end=20.0)
    assert np.abs(a.y - b.y).max() < 1e-11
    with pytest.raises(ValueError, match=r"structure matrix S\(y\) returned 3 values"):
        geomint.run(geomint.poisson(lambda y: 0.0, lambda y: y, lambda y: np.zeros(3), [1.0, 2.0]),
                    method="avf", steps=1)


def test_work_precision_from_python():
    wp = geomint.work_precision(["verlet", "yoshida-4"], "kepler", [0.1, 0.05, 0.025], 2.0)
    for m, row in wp.items():
        assert list(row) == ["dt", "steps", "force_evals", "seconds", "error"]
        slope = np.polyfit(np.log(row["dt"]), np.log(row["error"]), 1)[0]
        # measured slopes: verlet 2.01, yoshida-4 3.82
        assert slope == pytest.approx(geomint.method(m)["order"], abs=0.3), (m, slope)
    assert np.all(wp["yoshida-4"]["force_evals"] > wp["verlet"]["force_evals"])
    e = geomint.work_precision("verlet", "kepler", [0.1, 0.05], 10.0, error="energy")
    # measured 4.18
    assert e["verlet"]["error"][0] / e["verlet"]["error"][1] == pytest.approx(4.0, rel=0.1)
    # a problem without an exact solution needs a reference
    with pytest.raises(ValueError, match="no exact solution"):
        geomint.work_precision("verlet", "henon-heiles", [0.1], 1.0)
    r = geomint.work_precision("verlet", "henon-heiles", [0.1, 0.05], 1.0,
                               reference_method="kahan-li-8", reference_dt=0.01)
    assert r["verlet"]["error"][0] / r["verlet"]["error"][1] == pytest.approx(4.0, rel=0.05)  # 4.007
    from geomint import plot as gplot
    fig = gplot.work_precision(wp, cost="force_evals")
    assert fig.axes[0].get_xlabel() == "force evals"


def test_progress_callback_and_bar():
    calls = []
    r = geomint.run("kepler", dt=0.01, steps=10000, every=10000,
                    progress=lambda f, t: calls.append((f, t)))
    fractions = [f for f, _ in calls]
    assert fractions[0] == 0.0 and fractions[-1] == 1.0
    assert 150 <= len(calls) <= 260 and fractions == sorted(fractions)
    # observing never changes what a run computes
    np.testing.assert_array_equal(r.y[-1], geomint.run("kepler", dt=0.01, steps=10000,
                                                       every=10000).y[-1])
    # the bar: only on a terminal
    out = io.StringIO()
    bar = gprogress.Bar("kepler", stream=out, interval=0.0)
    geomint.run("kepler", dt=0.01, steps=1000, progress=bar)
    text = out.getvalue()
    assert text.endswith("\n") and "100.0%" in text and "kepler [" in text
    assert gprogress.resolve(True, "x") is None          # pytest's stderr is not a terminal

    class Tty(io.StringIO):
        def isatty(self):
            return True
    import sys
    old, sys.stderr = sys.stderr, Tty()
    try:
        geomint.run("kepler", dt=0.01, steps=100, progress=True)
        assert "100.0%" in sys.stderr.getvalue()
    finally:
        sys.stderr = old
    with pytest.raises(TypeError, match="progress: expected True"):
        geomint.run("kepler", steps=1, progress="yes")


def test_progress_raising_stops_the_run():
    def stop(f, t):
        if f > 0.5:
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt) as e:
        geomint.run("kepler", dt=0.01, steps=10000, progress=stop)
    assert "progress callback" in e.value.__notes__[0]
    assert 50.0 < e.value.geomint_time < 52.0
