"""Arrays: no copies for states and recorded runs (buffer addresses), argument checks, and
memory/refcounts stable over 10^5 create/free cycles."""
import resource
import sys

import numpy as np
import pytest

import geomint


def test_state_is_a_view_of_the_library_array():
    it = geomint.Integrator("kepler", "verlet")
    it.run(10, 0.01)
    s = it.state
    assert s.__array_interface__["data"][0] == it._it._state_address()
    assert not s.flags.writeable
    with pytest.raises(ValueError):
        s[0] = 1.0


def test_recorded_run_is_not_copied():
    r = geomint.run("kepler", dt=0.01, steps=100)
    base = r.y.__array_interface__["data"][0]
    assert r.q.__array_interface__["data"][0] == base
    assert r.p.__array_interface__["data"][0] == base + 8 * 2
    assert np.shares_memory(r.q, r.y) and np.shares_memory(r.p, r.y)


def test_callback_arguments_are_reused_read_only_buffers():
    seen = []

    def grad_V(q):
        seen.append(q)
        return q.copy()
    pb = geomint.separable(lambda q: 0.5 * q @ q, grad_V, [1.0], [0.0])
    geomint.run(pb, dt=0.1, steps=3)
    assert all(a is seen[0] for a in seen)
    assert not seen[0].flags.writeable


def rss_kb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() // 1024


def test_create_free_cycles_keep_memory_and_refcounts():
    def grad(q):
        return q
    pb0 = geomint.separable(lambda q: 0.5 * q @ q, grad, [1.0], [0.0])
    refs = sys.getrefcount(grad), sys.getrefcount(pb0)
    for i in range(2000):  # warm up allocator pools
        geomint.Integrator(pb0, "verlet").run(1, 0.1)
    before = rss_kb()
    for i in range(100000):
        it = geomint.Integrator("harmonic", "verlet", record=False) if i % 2 else \
            geomint.Integrator(pb0, "verlet")
        it.run(1, 0.1)
        del it
    after = rss_kb()
    # a leak of one 32-byte state per cycle would be 3 MB; measured growth 92 kB
    assert after - before < 1500, (before, after)
    assert (sys.getrefcount(grad), sys.getrefcount(pb0)) == refs


@pytest.mark.parametrize("kwargs,exc,text", [
    (dict(q0=[1.0, 2.0], p0=[1.0]), ValueError, "p0: expected 2 values"),
    (dict(q0=[[1.0]], p0=[1.0]), ValueError, "q0: expected a 1-D array"),
    (dict(q0=["a"], p0=[1.0]), TypeError, "q0: expected real numbers"),
    (dict(q0=[1 + 2j], p0=[1.0]), TypeError, "q0: expected real numbers"),
    (dict(q0=[np.nan], p0=[1.0]), ValueError, "q0: component 0 is nan"),
    (dict(q0=[1.0], p0=[np.inf]), ValueError, "p0: component 0 is inf"),
])
def test_bad_initial_arrays(kwargs, exc, text):
    with pytest.raises(exc, match=text):
        geomint.separable(lambda q: 0.0, lambda q: q, **kwargs)


def test_bad_scalar_arguments():
    with pytest.raises(ValueError, match="dt: must be finite"):
        geomint.run("kepler", dt=float("nan"), steps=10)
    with pytest.raises(ValueError, match="dt: must be non-zero"):
        geomint.run("kepler", dt=0.0, steps=10)
    with pytest.raises(TypeError, match="steps: expected an integer"):
        geomint.run("kepler", steps=1.5)
    with pytest.raises(ValueError, match="steps: must be >= 0"):
        geomint.run("kepler", steps=-1)
    with pytest.raises(ValueError, match="give steps or t_end"):
        geomint.run("kepler", steps=1, t_end=1.0)
    with pytest.raises(ValueError, match=r"set\['e'\]: must be finite"):
        geomint.run("kepler", set={"e": float("nan")})
    with pytest.raises(ValueError, match="y: expected 4 values"):
        geomint.Integrator("kepler").set_state(0.0, [1.0, 2.0])
    with pytest.raises(TypeError, match="grad_V: expected a callable"):
        geomint.separable(lambda q: 0.0, 3, [1.0], [0.0])
