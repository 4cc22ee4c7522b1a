"""The ODE layer: tables, built-in problems bitwise equal to the C library (through the CLI's
%.17g CSV), user callbacks equal to the built-in problems, t_end, set, order, checkpoints."""
import math

import numpy as np
import pytest

import geomint


def test_method_table_has_orders_flags_references():
    rows = {m["name"]: m for m in geomint.methods()}
    assert len(rows) > 50
    v = rows["verlet"]
    assert v["order"] == 2 and "symplectic" in v["flags"] and "symmetric" in v["flags"]
    assert v["accepts"] == ["separable"] and v["reference"]
    assert rows["gauss-2"]["order"] == 4 and "implicit" in rows["gauss-2"]["flags"]
    assert geomint.method("yoshida-6")["order"] == 6
    assert geomint.method("gauss-12")["order"] == 24  # built for any s, beyond the table


def test_problem_table_and_parameters():
    rows = {p["name"]: p for p in geomint.problems()}
    assert rows["kepler"]["params"][0][:2] == ("e", 0.6)
    k = geomint.problem("kepler", set={"e": 0.9})
    assert k.kind == "separable" and k.dim == 2 and k.state_size == 4
    np.testing.assert_array_equal(k.y0, [1 - 0.9, 0.0, 0.0, math.sqrt((1 + 0.9) / (1 - 0.9))])


@pytest.mark.parametrize("problem,method,dt,steps,sets", [
    ("kepler", "verlet", 0.01, 1000, ()),
    ("kepler", "yoshida-6", 0.05, 400, ("e=0.9",)),
    ("kepler", "gauss-2", 0.05, 200, ()),            # implicit, fixed-point on positions
    ("henon-heiles", "blanes-moan-6", 0.1, 300, ()),
    ("point-vortices", "lobatto-iiia-iiib-3", 0.02, 100, ()),
    ("lotka-volterra", "avf", 0.05, 100, ()),        # Poisson, discrete gradient
    ("rigid-body", "lgvi", 0.05, 200, ()),           # SO(3)
    ("harmonic", "rk4", 0.1, 100, ("q1=0.3",)),
])
def test_builtin_bitwise_equal_to_c(tmp_path, cli, problem, method, dt, steps, sets):
    summary, header, data = cli(tmp_path, problem, method, dt, steps=steps, sets=sets)
    params = dict(s.split("=") for s in sets)
    r = geomint.run(problem, method=method, dt=dt, steps=steps,
                    set={k: float(v) for k, v in params.items()})
    n = r.y.shape[1]
    assert r.y.shape[0] == data.shape[0] == steps + 1
    # every recorded state, every bit
    np.testing.assert_array_equal(r.t, data[:, 0])
    np.testing.assert_array_equal(r.y, data[:, 1:1 + n])
    assert r.stats["force_evals"] == summary["force_evals"]
    assert r.stats["steps"] == steps


def test_t_end_equals_c(tmp_path, cli):
    summary, _, data = cli(tmp_path, "kepler", "mclachlan-4", 0.03, t_end=2.0)
    r = geomint.run("kepler", method="mclachlan-4", dt=0.03, t_end=2.0)
    assert r.t_final == 2.0 == summary["final"]["t"]
    np.testing.assert_array_equal(r.q[-1], summary["final"]["q"])
    np.testing.assert_array_equal(r.p[-1], summary["final"]["p"])
    np.testing.assert_array_equal(r.y, data[:, 1:5])


def test_every_records_subsampled_states_without_changing_them():
    a = geomint.run("kepler", dt=0.01, steps=1000)
    b = geomint.run("kepler", dt=0.01, steps=1000, every=100)
    assert b.y.shape == (11, 4)
    np.testing.assert_array_equal(a.y[::100], b.y)


def kepler_user(e=0.6):
    """Kepler as a user problem, written with the C problem's arithmetic (src/problems/kepler.c)."""
    def V(q):
        return -1.0 / math.sqrt(q[0] * q[0] + q[1] * q[1])

    def grad_V(q):
        r = math.sqrt(q[0] * q[0] + q[1] * q[1])
        return q / (r * r * r)
    return geomint.separable(V, grad_V, [1 - e, 0.0], [0.0, math.sqrt((1 + e) / (1 - e))])


def test_user_separable_equals_builtin():
    pb = kepler_user()
    for method, dt in (("verlet", 0.01), ("yoshida-6", 0.05), ("gauss-2", 0.05)):
        a = geomint.run(pb, method=method, dt=dt, steps=300)
        b = geomint.run("kepler", method=method, dt=dt, steps=300)
        # the same arithmetic in the same order: equal to the last bit (measured: 0 difference)
        np.testing.assert_array_equal(a.y, b.y)
        assert a.stats == b.stats
    assert pb.energy(pb.y0) == -0.5


def test_user_hamiltonian_and_first_order_equal_builtin_to_roundoff():
    def H(q, p):
        return 0.5 * (p @ p) - 1.0 / np.sqrt(q @ q)

    def dH_dq(q, p):
        return q / np.sqrt(q @ q) ** 3

    def dH_dp(q, p):
        return p.copy()
    y0 = geomint.problem("kepler").y0
    ham = geomint.hamiltonian(H, dH_dq, dH_dp, y0[:2], y0[2:])
    a = geomint.run(ham, method="gauss-2", dt=0.05, steps=200)
    b = geomint.run("kepler", method="gauss-2", dt=0.05, steps=200)
    # measured max difference 2e-14 (different grouping of q/r^3 and of the Newton iterates)
    assert np.max(np.abs(a.y - b.y)) < 1e-11

    def f(t, y):
        q, p = y[:2], y[2:]
        return np.concatenate([p, -q / np.sqrt(q @ q) ** 3])
    fo = geomint.first_order(f, y0)
    c = geomint.run(fo, method="rk4", dt=0.01, steps=500)
    d = geomint.run("kepler", method="verlet", dt=1e-4, steps=50000, every=100)
    # rk4 at dt = 0.01 against verlet at 1e-4 (error ~1e-6 over t = 5); measured 2.6e-7
    assert np.max(np.abs(c.y[-1] - d.y[-1])) < 3e-6


def test_vectorized_force_called_once_per_evaluation():
    calls = []
    n = 50
    omega = np.linspace(1, 2, n)

    def grad_V(q):
        calls.append(1)
        return omega ** 2 * q
    pb = geomint.separable(lambda q: 0.5 * np.sum(omega ** 2 * q ** 2), grad_V,
                           np.ones(n), np.zeros(n))
    r = geomint.run(pb, method="verlet", dt=0.01, steps=100)
    assert len(calls) == r.stats["force_evals"] == 101


def test_observer_sees_the_states():
    seen = []
    r = geomint.run("kepler", dt=0.1, steps=20, every=5,
                    observer=lambda t, y: seen.append((t, y.copy())))
    assert [t for t, _ in seen] == list(r.t)
    np.testing.assert_array_equal(np.array([y for _, y in seen]), r.y)


def test_rigid_body_rotations():
    r = geomint.run("rigid-body", method="lgvi", dt=0.05, steps=100)
    assert r.R.shape == (101, 3, 3)
    err = np.abs(np.einsum("nij,nik->njk", r.R, r.R) - np.eye(3)).max()
    assert err < 1e-13  # measured 1.1e-15 (orthogonal to round-off)


def test_order_measured():
    o = geomint.order("yoshida-4", "kepler", t_end=1.0)
    assert o["declared"] == 4 and o["outcome"] == "measured"
    assert abs(o["order"] - 4) < 0.2


def test_checkpoint_restart_bitwise(tmp_path):
    full = geomint.Integrator("kepler", "yoshida-4").run(400, 0.02)
    it = geomint.Integrator("kepler", "yoshida-4", observer=None)
    path = tmp_path / "ck.bin"
    saved = []

    class Stop(Exception):
        pass

    def obs(t, y):
        if len(saved) == 0 and t >= 3.0:
            it.save(path)
            saved.append(t)
            raise Stop
    it2 = geomint.Integrator("kepler", "yoshida-4", observer=obs)
    it = it2
    with pytest.raises(Stop):
        it2.run(400, 0.02)
    fresh = geomint.Integrator("kepler", "yoshida-4")
    fresh.load(path)
    rest = fresh.resume()
    np.testing.assert_array_equal(rest.y[-1], full.y[-1])
    assert fresh.time == full.t_final


def test_user_lagrangian_equals_builtin_to_roundoff():
    # the damped oscillator with c = 0: L = v^2/2 - q^2/2 (src/problems, a Lagrangian model)
    ref = geomint.problem("damped-oscillator", set={"c": 0.0})
    q0, p0 = ref.y0[:1], ref.y0[1:]
    pb = geomint.lagrangian(lambda q, v: 0.5 * v @ v - 0.5 * q @ q, lambda q, v: -q,
                            lambda q, v: v.copy(), q0, p0)
    for method in ("vi-trapezoidal", "vi-midpoint", "vi-galerkin-gauss-3"):
        a = geomint.run(pb, method=method, dt=0.1, steps=100)
        b = geomint.run(ref, method=method, dt=0.1, steps=100)
        # measured max difference 1.1e-16 (trapezoidal, midpoint), 2.2e-16 (Galerkin): the user
        # problem has no Hessian, so Newton uses central differences (stats["fd_jacobians"])
        assert np.max(np.abs(a.y - b.y)) < 1e-13, method
