"""harminv and flux of Yee scenes, Maxwell on meshes (DEC leapfrog, AVI), the multisymplectic
PDE schemes: from Python against the CLI and the physics."""
import json
import os
import subprocess

import numpy as np
import pytest

import geomint
from geomint import dec, fields, pde, yee
from conftest import CLI, SOURCE


def cavity_scene(steps_time=40.0):
    # a 2-D TM PEC cavity 1 x 1 rung by a short pulse: modes f = ½ √(l² + m²), l, m >= 1
    return {
        "grid": {"dim": "2d-tm", "cells": [40, 40], "size": [1.0, 1.0]},
        "boundaries": {"x": "pec", "y": "pec"},
        "sources": [{"type": "point", "component": "Ez", "position": [0.31, 0.23],
                     "waveform": {"kind": "gaussian", "frequency": 1.0, "width": 0.3,
                                  "delay": 1.5}}],
        "probes": [{"name": "p", "component": "Ez", "position": [0.67, 0.59]}],
        "flux": [{"name": "mid", "axis": "x", "position": 0.5}],
        "run": {"time": steps_time},
    }


def test_yee_harminv_finds_cavity_modes_and_flux():
    sim = yee.Scene(cavity_scene())
    sim.run()
    modes = sim.harminv("p", 0.5, 1.2, t_min=4.0)
    good = modes["error"] < 1e-4
    f = np.sort(modes["frequency"][good])
    exact = sorted({0.5 * np.hypot(l, m) for l in range(1, 4) for m in range(1, 4)
                    if 0.5 < 0.5 * np.hypot(l, m) < 1.2})
    # (1,1) 0.70711, (1,2) 1.11803: measured 0.70707 and 1.11776 (2.2e-4: dispersion, h = 1/40)
    for fe in exact:
        assert np.min(np.abs(f - fe)) / fe < 1e-3, (fe, f)
    assert np.all(modes["q"][good] > 1e4)                # PEC: no loss (measured Q 5.9e4, 1.5e6)
    flux = sim.fluxes()
    assert set(flux) == {"mid"} and np.isfinite(flux["mid"])
    # the function itself: a synthetic decaying signal
    t = np.arange(2000) * 0.05
    s = np.exp(-0.01 * t) * np.cos(2 * np.pi * 0.8 * t + 0.3)
    m = fields.harminv(s, 0.05, 0.1, 2.0)
    i = int(np.argmax(m["amplitude"]))
    assert m["frequency"][i] == pytest.approx(0.8, rel=1e-12)  # measured 9e-16
    assert m["decay"][i] == pytest.approx(0.01, rel=1e-11)     # measured 1.8e-13
    with pytest.raises(geomint.Error, match="harminv"):
        fields.harminv(s[:4], 0.05, 0.1, 2.0)
    with pytest.raises(ValueError, match="signal: values must be finite"):
        fields.harminv(np.where(t > 1, np.nan, s), 0.05, 0.1, 2.0)
    with pytest.raises(KeyError, match="probe 'q'"):
        sim.harminv("q", 0.5, 1.2)


def test_yee_progress_in_pieces_is_bitwise():
    a, b = yee.Scene(cavity_scene(5.0)), yee.Scene(cavity_scene(5.0))
    calls = []
    a.run(progress=lambda f, t: calls.append(f))
    b.run()
    assert calls[0] == 0.0 and calls[-1] == 1.0 and len(calls) > 100
    np.testing.assert_array_equal(a.field("Ez"), b.field("Ez"))


def te11(cx):
    tri = cx.simplices(2)
    c = cx.vertices[tri].mean(axis=1)
    return np.cos(np.pi * c[:, 0]) * np.cos(np.pi * c[:, 1]) * cx.volumes(2)


def test_mesh_maxwell_leapfrog_cavity():
    cx = dec.Complex.rectangle(0, 1, 0, 1, 16, 18, "acute")
    m = fields.MeshMaxwell(cx)
    assert m.dt == pytest.approx(0.9 * m.cfl_limit)
    m.set_fields(np.zeros(cx.count(1)), te11(cx))
    probe = m.add_probe("Hz", (0.3, 0.2))
    e0 = m.energy()["leapfrog"]
    m.advance(int(40 / m.dt))
    # the leapfrog energy is exact without sources: measured 1.7e-15
    assert abs(m.energy()["leapfrog"] - e0) / e0 < 1e-14
    assert m.energy()["electric"] > 0.1 * e0                 # the mode oscillates
    assert np.abs(m.gauss()).max() < 1e-14                   # measured 1.5e-16
    assert m.E.shape == (cx.count(1),) and not m.E.flags.writeable
    t, v = m.probe(probe)
    modes = fields.harminv(v, t[1] - t[0], 0.3, 1.5)
    # TE11 of the unit square: f = 1/√2; measured 0.706784 (h ≈ 1/16)
    assert modes["frequency"][np.argmax(modes["amplitude"])] == pytest.approx(
        2 ** -0.5, rel=1e-3)


def test_mesh_maxwell_gmsh_avi_and_errors():
    right = dec.Complex.rectangle(0, 1, 0, 1, 4, 4, "right")
    with pytest.raises(geomint.Error, match="the mesh is not well-centred: 16 interior edges"):
        fields.MeshMaxwell(right)                            # the diagonal star needs it
    fields.MeshMaxwell(right, star="whitney")                # the Whitney star does not
    cx = dec.Complex.from_file(os.path.join(SOURCE, "tests/data/square_v41.msh"))
    m = fields.MeshMaxwell(cx, star="whitney")
    m.set_fields(np.zeros(cx.count(1)), te11(cx))
    e0 = m.energy()["leapfrog"]
    m.advance(200)
    assert abs(m.energy()["leapfrog"] - e0) / e0 < 1e-14     # measured 7.8e-16
    rect = dec.Complex.rectangle(0, 1, 0, 1, 8, 9, "acute")
    a = fields.MeshMaxwell(rect, scheme="avi")
    a.set_fields(np.zeros(rect.count(1)), te11(rect))
    p0 = a.energy()["plain"]
    a.advance_to(2.0)
    assert a.time == pytest.approx(2.0, abs=a.cfl_limit)
    # AVI: energy bounded (measured relative change -1.9e-3 at t = 2)
    assert abs(a.energy()["plain"] / p0 - 1) < 1e-2
    with pytest.raises(geomint.Error, match="AVI|advance_to"):
        a.advance(1)
    with pytest.raises(ValueError, match=r"E \(one value per edge\): expected"):
        m.set_fields(np.zeros(3))
    with pytest.raises(geomint.Error, match="CFL|limit"):
        fields.MeshMaxwell(rect, dt=1.0)
    with pytest.raises(ValueError, match=r"epsilon \(one per top simplex\)"):
        fields.MeshMaxwell(rect, epsilon=np.ones(3))
    with pytest.raises(geomint.Error, match="epsilon|ε"):
        fields.MeshMaxwell(rect, epsilon=-np.ones(rect.count(2)))
    with pytest.raises(ValueError, match="scheme: 'leapfrog' or 'avi'"):
        fields.MeshMaxwell(rect, scheme="yee")


def test_mesh_box_3d_leapfrog():
    cx = dec.Complex.box((0, 0, 0), (1, 1, 1), (3, 3, 3))
    assert cx.dim == 3 and cx.count(3) == 6 * 27
    m = fields.MeshMaxwell(cx, star="whitney")
    rng = np.random.default_rng(1)
    m.set_fields(rng.standard_normal(cx.count(1)))
    e0 = m.energy()["leapfrog"]
    m.advance(50)
    assert abs(m.energy()["leapfrog"] - e0) / e0 < 1e-14    # measured 1.8e-16
    assert m.div_b() < 1e-14                                 # measured 2.8e-16


def test_pde_sine_gordon_against_cli(tmp_path):
    # `geomint pde run sine-gordon`: the standing breather (ω = 0.5) at t = 0, n = 41 on [-20, 20)
    n, h, k = 41, 40.0 / 41, np.sqrt(0.75)
    x = pde.points("preissmann", n, h, -20.0)
    s0 = np.column_stack([0 * x, 4 * k / np.cosh(k * x), 0 * x])
    p = pde.Pde("sine-gordon", "preissmann", s0, h=h, dt=0.1, x0=-20.0)
    p.advance(10)
    out = subprocess.run([CLI, "pde", "run", "sine-gordon", "--scheme", "preissmann", "--n",
                          "41", "--dt", "0.1", "--T", "1", "--out", str(tmp_path / "s.csv"),
                          "--json"], capture_output=True, text=True, check=True).stdout
    ref = json.loads(out)
    data = np.loadtxt(tmp_path / "s.csv", delimiter=",", skiprows=1)
    # the same scheme to round-off (measured 2e-14: NumPy's cosh against the CLI's)
    assert np.abs(data[:, 1:4] - p.state).max() < 1e-12
    assert p.invariants()["energy"] == pytest.approx(ref["energy"], rel=1e-13)
    assert p.steps == 10 and p.time == pytest.approx(1.0)
    assert not p.state.flags.writeable


def test_pde_nls_norm_and_schemes():
    names = [s["name"] for s in pde.schemes()]
    assert {"preissmann", "euler-box", "ms", "gauss-prk"} <= set(names)
    n, L = 101, 20.0
    h = L / n
    x = pde.points("preissmann", n, h, -L / 2)
    psi = 1 / np.cosh(x)                                     # the soliton at rest
    s0 = np.column_stack([psi, 0 * x, -np.tanh(x) / np.cosh(x), 0 * x])
    p = pde.Pde("nls", "preissmann", s0, h=h, dt=0.05, x0=-L / 2)
    n0 = p.invariants()["norm"]
    calls = []
    p.advance(200, progress=lambda f, t: calls.append(t))
    # Preissmann keeps the discrete charge exactly: measured 8.9e-16 relative
    assert abs(p.invariants()["norm"] - n0) / n0 < 1e-14
    assert calls[-1] == pytest.approx(10.0)
    amp = np.hypot(p.state[:, 0], p.state[:, 1])
    assert np.abs(amp - psi).max() < 0.03                    # |ψ| stays a sech (measured 0.011)
    with pytest.raises(ValueError, match=r"s0: expected shape \(n, 4\) for nls"):
        pde.Pde("nls", "preissmann", s0[:, :3], h=h, dt=0.05)
    with pytest.raises(geomint.Error, match="unknown PDE scheme 'preisman'; did you mean: "
                       "preissmann"):
        pde.Pde("nls", "preisman", s0, h=h, dt=0.05)
    with pytest.raises(geomint.Error, match="even|odd"):
        pde.Pde("sine-gordon", "preissmann", np.zeros((40, 3)), h=1.0, dt=0.1)
    with pytest.raises(ValueError, match="s0: point 3 component 1 is not finite"):
        bad = s0.copy()
        bad[3, 1] = np.inf
        pde.Pde("nls", "preissmann", bad, h=h, dt=0.05)


def test_new_objects_create_free_cycles_keep_memory():
    from test_arrays import rss_kb
    import sys
    rect = dec.Complex.rectangle(0, 1, 0, 1, 3, 3, "acute")
    s0 = np.zeros((5, 3))
    I = np.array([2.0, 1.0, 0.5])
    grad = lambda y: y / I  # noqa: E731

    def cycle(i):
        m = fields.MeshMaxwell(rect)
        m.advance(1)
        _ = m.E, m.B
        p = pde.Pde("sine-gordon", "lf", s0, h=1.0, dt=0.5)
        p.advance(1)
        _ = p.state
        pb = geomint.poisson(lambda y: 0.0, grad, lambda y: np.zeros((3, 3)), [1.0, 0, 0])
        geomint.run(pb, method="avf", dt=0.1, steps=1)
        geomint.run(geomint.rigid_body(I, [0, 0, 1.0], V=lambda R: 0.0,
                                       grad_V=lambda R: np.zeros(3)), method="lgvi", steps=1)
        fields.harminv(np.cos(np.arange(64) * 0.3), 1.0, 0.01, 0.5)
    refs = sys.getrefcount(rect), sys.getrefcount(grad)
    for i in range(100):
        cycle(i)
    before = rss_kb()
    for i in range(500):
        cycle(i)
    after = rss_kb()
    # a leak of one 64-byte block per object and cycle would be 160 kB; measured growth 0 kB
    # (the Python objects' own cycles: test_arrays, 10^5 cycles)
    assert after - before < 100, (before, after)
    assert (sys.getrefcount(rect), sys.getrefcount(grad)) == refs
