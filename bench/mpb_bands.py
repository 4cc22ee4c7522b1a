#!/usr/bin/env python3
"""geomint maxwell bands against MPB (Debian mpb) on one scene, in the same run: a square
lattice of dielectric rods (eps 8.9, radius 0.2a, TM), 5 bands at 25 k points along G-X-M-G,
32 cells per period, subpixel smoothing in both (geomint's eps_averaging default; MPB's
mesh averaging default). MPB gets geomint's k points verbatim. Prints each band's largest
relative difference |f_geomint - f_MPB| / f_MPB (every MPB value in (0, f_max] matched to the
nearest geomint frequency at that k; a degenerate pair is one geomint frequency) and the wall
time ratio (min of --repeat runs each). Skipped with a message when mpb is not installed.

usage: bench/mpb_bands.py [BUILD_DIR] [--points N] [--repeat R] [--res N]
"""
import json, os, resource, shutil, subprocess, sys, tempfile, time

args = sys.argv[1:]
def opt(name, default):
    if name in args:
        i = args.index(name); v = args[i + 1]; del args[i:i + 2]; return type(default)(v)
    return default
points, repeat, res = opt("--points", 25), opt("--repeat", 1), opt("--res", 32)
build = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build")
geomint = os.path.join(build, "geomint")
if shutil.which("mpb") is None:
    print("mpb_bands: skipped: mpb is not installed (Debian package mpb)"); sys.exit(0)
f_max, n_bands = 1.0, 5
work = tempfile.mkdtemp(prefix="mpb-bands-")
scene = os.path.join(work, "rods.json")
with open(scene, "w") as f:
    json.dump({"grid": {"dim": "2d-tm", "cells": [res, res], "size": [1, 1]},
               "materials": [{"shape": "cylinder", "center": [0.5, 0.5], "radius": 0.2,
                              "epsilon": 8.9}],
               "boundaries": {"x": "periodic", "y": "periodic"}, "run": {"time": 1}}, f)

def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime

def run_geomint():
    t, c = time.perf_counter(), cpu()
    out = subprocess.run([geomint, "maxwell", "bands", scene, "--k-path", "G,X,M,G", "--points",
                          str(points), "--bands", str(n_bands), "--f-min", "0.02", "--f-max", str(f_max), "--json",
                          "--no-plot", "--out", os.path.join(work, "g")],
                         check=True, capture_output=True, text=True,
                         env=dict(os.environ, OMP_NUM_THREADS="1")).stdout
    return time.perf_counter() - t, cpu() - c, json.loads(out)

def run_mpb(ks):
    ctl = os.path.join(work, "rods.ctl")
    with open(ctl, "w") as f:
        f.write("(set! num-bands %d)\n(set! k-points (list %s))\n" % (
            n_bands, " ".join("(vector3 %.12g %.12g 0)" % (k[0], k[1]) for k in ks)))
        f.write("(set! geometry (list (make cylinder (center 0 0 0) (radius 0.2) (height infinity)"
                " (material (make dielectric (epsilon 8.9))))))\n"
                "(set! geometry-lattice (make lattice (size 1 1 no-size)))\n"
                "(set! resolution %d)\n(run-tm)\n" % res)
    t, c = time.perf_counter(), cpu()
    out = subprocess.run(["mpb", ctl], check=True, capture_output=True, text=True, cwd=work,
                         env=dict(os.environ, OMP_NUM_THREADS="1")).stdout
    wall, used = time.perf_counter() - t, cpu() - c
    rows = [l.split(",") for l in out.splitlines() if l.startswith("tmfreqs:") and "k index" not in l]
    return wall, used, [[float(x) for x in r[6:6 + n_bands]] for r in rows]

tg, tm, cg, cm, g, m = [], [], [], [], None, None
for _ in range(repeat):  # interleaved, min of each
    w, c, g = run_geomint(); tg.append(w); cg.append(c)
    w, c, m = run_mpb([p["k"] for p in g["k_points"]]); tm.append(w); cm.append(c)
worst = [0.0] * n_bands
for p, mk in zip(g["k_points"], m):
    fg = [x for x in p["frequencies"] if x is not None]
    for b, fm in enumerate(mk):
        if fm <= 0 or fm > f_max: continue  # the static mode at G, bands above the search
        d = min((abs(x - fm) / fm for x in fg), default=float("inf"))
        worst[b] = max(worst[b], d)
print("mpb_bands: %d k points G-X-M-G, %d bands, %d cells per period, eps 8.9 rods r 0.2, TM"
      % (len(m), n_bands, res))
for b in range(n_bands):
    print("  band %d: max |f - f_MPB| / f_MPB = %.3e" % (b + 1, worst[b]))
print("  lost %d, extra %d (geomint's counts)" % (g["lost"], g["extra"]))
print("  wall (min of %d, one thread): geomint %.3f s, MPB %.3f s, ratio %.1fx"
      % (repeat, min(tg), min(tm), min(tg) / min(tm)))
print("  CPU time (user + sys, min of %d; steadier under load): geomint %.3f s, MPB %.3f s, "
      "ratio %.1fx" % (repeat, min(cg), min(cm), min(cg) / min(cm)))
shutil.rmtree(work)
