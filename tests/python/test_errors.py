"""Every exception path: library statuses as geomint.Error with the library's message,
callbacks that raise, solver failure."""
import math

import numpy as np
import pytest

import geomint


def test_bad_method_name_suggests():
    with pytest.raises(geomint.Error, match=r"unknown method 'verlte'; did you mean: verlet") as e:
        geomint.run("kepler", method="verlte")
    assert e.value.code == -3 and e.value.reason == "no such name"
    with pytest.raises(geomint.Error, match="did you mean: yoshida-6"):
        geomint.method("yoshida6")


def test_bad_problem_name_suggests():
    with pytest.raises(geomint.Error, match=r"unknown problem 'keplr'; did you mean: kepler"):
        geomint.run("keplr")


def test_bad_parameter_carries_library_message():
    with pytest.raises(geomint.Error, match=r"eccentricity e must be in \[0, 1\), got 1.5"):
        geomint.problem("kepler", set={"e": 1.5})
    with pytest.raises(geomint.Error, match="kepler: set ecc"):
        geomint.problem("kepler", set={"ecc": 0.5})


def test_method_cannot_integrate_problem():
    with pytest.raises(geomint.Error, match="verlet") as e:
        geomint.run("lotka-volterra", method="verlet")
    assert e.value.reason == "method cannot integrate this problem"


def test_unknown_solver():
    with pytest.raises(geomint.Error, match="unknown solver 'newtn'"):
        geomint.run("kepler", method="gauss-2", solver="newtn")


def test_nan_state_from_the_library():
    it = geomint.Integrator("kepler")
    with pytest.raises(geomint.Error, match="non-finite|NaN|nan") as e:
        it._it.set_state(0.0, np.array([np.nan, 0, 0, 1.0]))  # past the Python checks
    assert e.value.code == -7


def test_state_becoming_nan_names_the_step():
    # a force that returns NaN at some point: the library stops with the step and component
    def grad_V(q):
        return q if q[0] > 0 else np.full(1, np.nan)
    pb = geomint.separable(lambda q: 0.5 * q @ q, grad_V, [1.0], [0.0])
    with pytest.raises(geomint.Error, match=r"state component .* became nan in step") as e:
        geomint.run(pb, dt=0.1, steps=100)
    assert e.value.code == -7


class Boom(Exception):
    pass


def test_raising_force_stops_and_reraises_with_time():
    def grad_V(q):
        if q[0] < 0:
            raise Boom("negative")
        return q
    pb = geomint.separable(lambda q: 0.5 * q @ q, grad_V, [1.0], [0.0])
    with pytest.raises(Boom, match="negative") as e:
        geomint.run(pb, dt=0.1, steps=100)
    # q = cos t first becomes negative after t = pi/2: the step from t = 1.5 (verlet's kick
    # at the end of the step from 1.5 to 1.6)
    assert e.value.geomint_time == pytest.approx(1.5)
    assert "potential gradient" in e.value.__notes__[0]


def test_raising_rhs_reports_its_own_time():
    def f(t, y):
        if t > 0.25:
            raise Boom(f"t={t}")
        return -y
    with pytest.raises(Boom) as e:
        geomint.run(geomint.first_order(f, [1.0]), method="rk4", dt=0.1, steps=10)
    assert e.value.geomint_time == pytest.approx(0.3)
    assert "at t = 0.3" in e.value.__notes__[0]


def test_raising_observer_and_wrong_result_size():
    def obs(t, y):
        if t > 0.5:
            raise Boom("observer")
    with pytest.raises(Boom):
        geomint.run("kepler", dt=0.1, steps=10, observer=obs)
    pb = geomint.separable(lambda q: 0.0, lambda q: np.zeros(3), [1.0, 2.0], [0.0, 0.0])
    with pytest.raises(ValueError, match="potential gradient returned 3 values, expected 2"):
        geomint.run(pb, steps=1)
    pb = geomint.separable(lambda q: 0.0, lambda q: "x", [1.0], [0.0])
    with pytest.raises(ValueError):
        geomint.run(pb, steps=1)


def test_solver_failure_is_an_error():
    # a stiff linear problem with a huge step: fixed-point iteration of gauss-2 diverges
    pb = geomint.first_order(lambda t, y: -10.0 * y, [1.0])
    with pytest.raises(geomint.Error, match="fixed-point iteration did not converge in 200 "
                       "iterations .* in the step from t = 0") as e:
        geomint.run(pb, method="gauss-2", solver="fixed-point", dt=1.0, steps=2)
    assert e.value.code == -4 and e.value.reason == "iteration did not converge"


def test_checkpoint_errors(tmp_path):
    it = geomint.Integrator("kepler")
    with pytest.raises(geomint.Error):
        it.load(tmp_path / "missing.bin")
    (tmp_path / "junk.bin").write_bytes(b"not a checkpoint")
    with pytest.raises(geomint.Error):
        it.load(tmp_path / "junk.bin")
