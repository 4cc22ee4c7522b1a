#!/usr/bin/env python3
"""The Python package against C and against SciPy, ratios measured in one run.

    bench/python_overhead.py [--quick] [--json FILE] [--only tolerance|energy] [--figure PNG]

Needs the geomint package (python/, see docs/python.md) and, for the binding comparison,
Debian's python3-cffi and a C compiler. Measures:
  1. overhead of a built-in problem run from Python over the same run from C
     (bench/python_c_baseline.c, built as BUILD/bench_python_c_baseline; BUILD from
     GEOMINT_BUILD_DIR, default build/): Kepler (verlet, 10^6 steps) and the outer solar
     system (10^5 steps);
  2. a Python-defined force: time per force evaluation inside a verlet run over the floor,
     the bare cost of calling the same Python function in a loop from C (and from Python);
     the same trampoline written with cffi (API mode, extern "Python") for comparison;
  3. time to a final position error <= 1e-8 after 200 periods of Kepler, e = 0.6, with the
     same Python force: geomint's splitting/composition rows against scipy.integrate.solve_ivp
     (RK45, DOP853, Radau);
  4. the energy error after 10^4 periods of the same Kepler problem at equal CPU time: DOP853
     at --energy-rtol, then geomint's kahan-li-8 with the steps that fill the same time.
--only tolerance|energy runs part 3 or 4 alone; --figure-from A.json B.json merges results.
Timings are CPU times of the thread (time.thread_time; the C side CLOCK_THREAD_CPUTIME_ID),
best of a few repeats; prints a table and, last, one JSON line.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import geomint
from geomint import _core

HERE = os.path.dirname(os.path.abspath(__file__))
BUILD = os.environ.get("GEOMINT_BUILD_DIR", os.path.join(HERE, "..", "build"))
BASELINE = os.path.join(BUILD, "bench_python_c_baseline")


def best(fn, repeats=3, clock=time.thread_time):
    """Best of `repeats` runs of fn by the thread's CPU time (robust to the other processes
    on a shared machine; every measured loop is single-threaded)."""
    times = []
    for _ in range(repeats):
        t = clock()
        fn()
        times.append(clock() - t)
    return min(times)


# ---- 1. built-in problems: Python over C -----------------------------------------------------

def builtin_overhead(problem, method, dt, steps, repeats):
    it = [None]

    def py_run():
        it[0].run(steps, dt)

    c_times, py_times = [], []
    for _ in range(repeats):  # interleaved, so that both see the same load
        out = subprocess.run([BASELINE, "/tmp", problem, method, repr(dt), str(steps), "2"],
                             capture_output=True, text=True, check=True)
        c_row = json.loads(out.stdout)
        c_times.append(c_row["cpu_s"])
        it[0] = geomint.Integrator(problem, method, every=steps)
        py_run_time = best(py_run, 1)
        py_times.append(py_run_time)
    c, py = min(c_times), min(py_times)
    final_q = c_row["final_q"]
    same = bool(np.array_equal(it[0].state[:len(final_q)], final_q))
    return {"problem": problem, "method": method, "steps": steps, "c_s": c, "python_s": py,
            "ratio": py / c, "bitwise_equal_final_q": same}


# ---- 2. a Python force: per evaluation over the floor ------------------------------------------

def kepler_force(q):
    return q / (q @ q) ** 1.5


def kepler_problem(e=0.6):
    return geomint.separable(lambda q: -1.0 / math.sqrt(q @ q), kepler_force,
                             [1 - e, 0.0], [0.0, math.sqrt((1 + e) / (1 - e))])


CFFI_SOURCE = r"""
static int py_force(void *ctx, const double *q, double *out);
/* the library's side of a force evaluation, as geomint's verlet makes it: call the force on
 * the current positions, use the result */
int loop(size_t n, size_t dim) {
  double q[64], out[64];
  for (size_t i = 0; i < dim; ++i) q[i] = 1.0 + (double)i;
  for (size_t k = 0; k < n; ++k) {
    if (py_force(NULL, q, out)) return 1;
    q[0] += 1e-12 * out[0];
  }
  return 0;
}
"""


def cffi_trampoline(n, dim=2):
    """Per-evaluation time of the same trampoline (copy q into a persistent array, call,
    copy the result out) written with cffi in API mode; None when cffi is missing."""
    try:
        import cffi
    except ImportError:
        return None
    tmp = tempfile.mkdtemp(prefix="gm_cffi_")
    ffi = cffi.FFI()
    ffi.cdef('extern "Python" int py_force(void *, const double *, double *);'
             "int loop(size_t n, size_t dim);")
    ffi.set_source("_gm_cffi_bench", CFFI_SOURCE)
    ffi.compile(tmpdir=tmp, verbose=False)
    sys.path.insert(0, tmp)
    import _gm_cffi_bench as mod
    f, lib = mod.ffi, mod.lib
    qa = np.zeros(dim)
    qptr = f.cast("double *", qa.ctypes.data)
    nbytes = dim * 8

    @f.def_extern()
    def py_force(ctx, q, out):
        f.memmove(qptr, q, nbytes)
        res = np.ascontiguousarray(kepler_force(qa), dtype=np.float64)
        f.memmove(out, f.cast("double *", res.ctypes.data), nbytes)
        return 0
    return best(lambda: lib.loop(n, dim)) / n


def python_force(n):
    q = np.array([0.4, 0.3])
    q.flags.writeable = False
    floor_c = best(lambda: _core._call_loop(kepler_force, q, n)) / n

    def py_loop():
        for _ in range(n):
            kepler_force(q)
    floor_py = best(py_loop) / n
    pb = kepler_problem()
    it = [None]

    def run():
        it[0] = geomint.Integrator(pb, "verlet", every=n)
        it[0].run(n, 1e-3)
    t = best(run)
    per_eval = t / it[0].stats["force_evals"]
    cffi = cffi_trampoline(n)
    return {"evaluations": n, "floor_c_ns": floor_c * 1e9, "floor_python_loop_ns": floor_py * 1e9,
            "geomint_per_eval_ns": per_eval * 1e9, "ratio": per_eval / floor_c,
            "cffi_per_eval_ns": cffi * 1e9 if cffi else None,
            "cffi_ratio": cffi / floor_c if cffi else None}


# ---- 3. against solve_ivp -------------------------------------------------------------------------

def kepler_error(q, q0):
    return float(np.max(np.abs(np.asarray(q) - q0)))


def geomint_to_tolerance(method, periods, tol):
    """The fewest steps per period reaching tol on the built-in Kepler (C force): steps per
    period grow by 2^(1/4) from 16 to the first that reaches it, then every integer from the
    last that did not is tried (the error need not be monotone in the step: the first that
    reaches tol counts); then the timed run with the Python force at that step."""
    t_end = 2 * math.pi * periods
    ref = geomint.problem("kepler")
    q0 = ref.y0[:2]

    def reaches(spp):
        it = geomint.Integrator(ref, method, every=10 ** 9)
        it.integrate(t_end, 2 * math.pi / spp)
        return kepler_error(it.state[:2], q0) <= tol

    below, steps_per_period = 8, 16
    while steps_per_period < 2 ** 16 and not reaches(steps_per_period):
        below = steps_per_period
        steps_per_period = int(math.ceil(steps_per_period * 2 ** 0.25))
    for spp in range(below + 1, steps_per_period):
        if reaches(spp):
            steps_per_period = spp
            break
    pb = kepler_problem()
    holder = [None]

    def run():
        it = geomint.Integrator(pb, method, every=10 ** 9)
        it.integrate(t_end, 2 * math.pi / steps_per_period)
        holder[0] = it
    # the Python force rounds differently from the C force: near the threshold its run may
    # miss tol where the C run reached it; then the next integer counts
    while True:
        seconds = best(run, 2)
        it = holder[0]
        if kepler_error(it.state[:2], q0) <= tol or steps_per_period >= 2 ** 16:
            break
        steps_per_period += 1
    return {"solver": f"geomint {method}", "seconds": seconds,
            "error": kepler_error(it.state[:2], q0), "force_evals": it.stats["force_evals"],
            "steps_per_period": steps_per_period}


def scipy_to_tolerance(method, periods, tol, budget_s):
    """The loosest rtol (half decades from 1e-8, atol = rtol/100) whose run reaches tol, and
    its CPU time; stops when the runs so far used more than budget_s of CPU time."""
    from scipy.integrate import solve_ivp
    t_end = 2 * math.pi * periods
    y0 = geomint.problem("kepler").y0
    q0 = y0[:2]
    counter = [0]

    def rhs(t, y):
        counter[0] += 1
        return np.concatenate([y[2:], -kepler_force(y[:2])])
    spent = 0.0
    for rtol in [10.0 ** (-k / 2) for k in range(16, 29)]:  # 1e-8 .. 1e-14
        counter[0] = 0
        t = time.thread_time()
        sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, rtol=rtol, atol=rtol * 1e-2)
        seconds = time.thread_time() - t
        spent += seconds
        err = kepler_error(sol.y[:2, -1], q0) if sol.success else math.inf
        if err <= tol:
            evals = counter[0]
            # best of two, as the geomint rows
            t = time.thread_time()
            solve_ivp(rhs, (0.0, t_end), y0, method=method, rtol=rtol, atol=rtol * 1e-2)
            seconds = min(seconds, time.thread_time() - t)
            return {"solver": f"scipy {method}", "seconds": seconds, "error": err,
                    "force_evals": evals, "rtol": rtol}
        if spent > budget_s:
            return {"solver": f"scipy {method}", "seconds": None, "error": err,
                    "force_evals": counter[0], "rtol": rtol,
                    "note": f"not reached within a {budget_s:.0f} s CPU budget (last rtol {rtol:g})"}
    return {"solver": f"scipy {method}", "seconds": None, "error": err, "rtol": rtol,
            "note": "not reached down to rtol 1e-14"}


# ---- 4. energy error after many periods at equal CPU time ------------------------------------

def energy_at_equal_time(periods, rtol, method="kahan-li-8"):
    """DOP853 at rtol over `periods` Kepler periods (e = 0.6, the Python force), its CPU time
    T; then geomint's `method` with the steps per period that fill T at the per-evaluation
    cost measured on a short run (rounded down, so geomint gets at most SciPy's time). Energy
    errors |H/H0 - 1| at 101 equally spaced times (SciPy: its dense output at t_eval)."""
    from scipy.integrate import solve_ivp
    pb = kepler_problem()
    y0 = pb.y0
    t_end = 2 * math.pi * periods
    h0 = pb.energy(y0)

    def rhs(t, y):
        return np.concatenate([y[2:], -kepler_force(y[:2])])
    times = np.linspace(0.0, t_end, 101)
    c = time.thread_time()
    sol = solve_ivp(rhs, (0.0, t_end), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-2,
                    t_eval=times)
    scipy_s = time.thread_time() - c
    scipy_err = np.array([abs(pb.energy(y) / h0 - 1) for y in sol.y.T])
    # geomint's cost per step from a short run, the steps per period that fill scipy_s, then
    # corrected by a run over 2% of the periods at that step; 0.8 of it as a margin (noise)
    it = geomint.Integrator(pb, method, every=10 ** 9)
    c = time.thread_time()
    it.run(2000, 0.01)
    spp = int(scipy_s / ((time.thread_time() - c) / 2000 * periods))
    if spp >= 4:
        part = max(1, periods // 50)
        it = geomint.Integrator(pb, method, every=10 ** 9)
        c = time.thread_time()
        it.run(spp * part, 2 * math.pi / spp)
        spp = int(0.8 * spp * scipy_s / ((time.thread_time() - c) * periods / part))
    out = {"periods": periods, "scipy_rtol": rtol, "scipy_s": scipy_s,
           "scipy_evals": int(sol.nfev), "scipy_final": float(scipy_err[-1]),
           "scipy_max": float(scipy_err.max()), "method": method, "steps_per_period": spp,
           "scipy_times": times.tolist(), "scipy_errors": scipy_err.tolist()}
    if spp < 4:
        out["note"] = f"SciPy's {scipy_s:.2f} s buys geomint fewer than 4 steps per period"
        return out
    it = geomint.Integrator(pb, method, every=spp * periods // 100)
    c = time.thread_time()
    r = it.run(spp * periods, 2 * math.pi / spp)
    geomint_s = time.thread_time() - c
    err = r.rel_energy_error()
    out.update({"geomint_s": geomint_s, "geomint_evals": it.stats["force_evals"],
                "geomint_final": float(err[-1]), "geomint_max": float(err.max()),
                "geomint_times": r.t.tolist(), "geomint_errors": err.tolist()})
    out["ratio_max"] = out["scipy_max"] / out["geomint_max"]
    out["ratio_final"] = out["scipy_final"] / max(out["geomint_final"], 1e-300)
    return out


def figure(result, path):
    """Bars of the CPU time to 1e-8 of every solver and, when measured, the energy error at
    equal CPU time against the periods (from a result of this script)."""
    import geomint.plot  # noqa: F401  (selects the Agg backend)
    import matplotlib.pyplot as plt
    k = result["kepler_to_1e-8"]
    rows = k["rows"]
    e = result.get("energy_equal_time")
    if e and "geomint_errors" in e:
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 3.6),
                                      gridspec_kw={"width_ratios": [1.2, 1]})
        period = 2 * math.pi
        ax2.semilogy(np.array(e["geomint_times"][1:]) / period,
                     np.maximum(e["geomint_errors"][1:], 1e-17),
                     label=f"geomint {e['method']} ({e['geomint_s']:.1f} s)")
        ax2.semilogy(np.array(e["scipy_times"][1:]) / period,
                     np.maximum(e["scipy_errors"][1:], 1e-17),
                     label=f"scipy DOP853 rtol {e['scipy_rtol']:g} ({e['scipy_s']:.1f} s)")
        ax2.set_xlabel("periods")
        ax2.set_ylabel("|H/H0 - 1|")
        ax2.set_title("energy error at equal CPU time")
        ax2.legend(fontsize=8)
    else:
        fig, ax = plt.subplots(figsize=(6.4, 3.4))
    names = [r["solver"] for r in rows]
    secs = [r["seconds"] if r["seconds"] is not None else 0.0 for r in rows]
    colors = ["tab:blue" if n.startswith("geomint") else "tab:orange" for n in names]
    ax.barh(names, secs, color=colors)
    top = max(secs) if max(secs) > 0 else 1.0
    for i, r in enumerate(rows):
        text = (f"{r['seconds']:.2f} s, {r['force_evals']} evals" if r["seconds"] is not None
                else f"not reached (error {r['error']:.1e} at rtol {r['rtol']:g})")
        ax.text(secs[i] + 0.01 * top, i, text, va="center", fontsize=8)
    ax.invert_yaxis()
    ax.set_xlim(0, top * 1.9)
    ax.set_xlabel("CPU seconds to a final position error of 1e-8")
    ax.set_title(f"Kepler e = {k['e']}, {k['periods']} periods, the same Python force")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="smaller sizes (a smoke test)")
    ap.add_argument("--json", help="also write the result to this file")
    ap.add_argument("--periods", type=int, help="Kepler periods of part 3 (default 200, quick 20)")
    ap.add_argument("--budget", type=float,
                    help="CPU seconds a SciPy method may spend on its tolerances (default 150)")
    ap.add_argument("--figure", help="draw the solve_ivp comparison into this PNG")
    ap.add_argument("--figure-from", nargs="+",
                    help="only draw --figure from JSON results of this script (merged)")
    ap.add_argument("--energy-periods", type=int,
                    help="periods of part 4, energy at equal time (default 10^4, quick 100)")
    ap.add_argument("--energy-rtol", type=float, default=1e-8,
                    help="DOP853's rtol in part 4 (default 1e-8)")
    ap.add_argument("--only", choices=["tolerance", "energy"],
                    help="run only part 3 (time to 1e-8) or part 4 (energy at equal time)")
    args = ap.parse_args()
    if args.figure_from:
        merged = {}
        for name in args.figure_from:
            with open(name) as f:
                merged.update(json.load(f))
        figure(merged, args.figure)
        return
    quick = args.quick
    out = {}
    if args.only is None:
        out.update(binding_overhead(quick))
    if args.only in (None, "tolerance"):
        out.update(to_tolerance(args, quick))
    if args.only in (None, "energy"):
        periods = args.energy_periods or (100 if quick else 10 ** 4)
        e = out["energy_equal_time"] = energy_at_equal_time(periods, args.energy_rtol)
        if "geomint_s" in e:
            print(f"energy after {periods} periods at equal CPU time: DOP853 rtol "
                  f"{e['scipy_rtol']:g} {e['scipy_s']:.2f} s, max |dH/H| {e['scipy_max']:.2e}; "
                  f"geomint {e['method']} ({e['steps_per_period']} steps per period) "
                  f"{e['geomint_s']:.2f} s, max {e['geomint_max']:.2e}; ratio "
                  f"{e['ratio_max']:.3g}")
        else:
            print(e["note"])
    if args.figure and "kepler_to_1e-8" in out:
        figure(out, args.figure)
    line = json.dumps(out)
    if args.json:
        with open(args.json, "w") as f:
            f.write(line + "\n")
    print("PYTHON_BENCH " + line)


def binding_overhead(quick):
    out = {}
    out["builtin"] = [builtin_overhead("kepler", "verlet", 1e-3, 10 ** 5 if quick else 10 ** 6, 5),
                      builtin_overhead("outer-solar-system", "verlet", 10.0,
                                       10 ** 4 if quick else 10 ** 5, 5)]
    for r in out["builtin"]:
        print(f"{r['problem']:20s} {r['method']} {r['steps']} steps: C {r['c_s']:.4f} s, "
              f"Python {r['python_s']:.4f} s, ratio {r['ratio']:.3f}, final q bitwise equal: "
              f"{r['bitwise_equal_final_q']}")
    out["python_force"] = pf = python_force(10 ** 4 if quick else 2 * 10 ** 5)
    print(f"Python force: floor (C loop calling it) {pf['floor_c_ns']:.0f} ns, Python loop "
          f"{pf['floor_python_loop_ns']:.0f} ns; per evaluation in a verlet run "
          f"{pf['geomint_per_eval_ns']:.0f} ns (ratio {pf['ratio']:.3f}); cffi trampoline "
          + (f"{pf['cffi_per_eval_ns']:.0f} ns (ratio {pf['cffi_ratio']:.3f})"
             if pf["cffi_per_eval_ns"] else "not measured (no cffi)"))
    return out


def to_tolerance(args, quick):
    out = {}
    periods, tol = args.periods or (20 if quick else 200), 1e-8
    budget = args.budget or (30 if quick else 150)
    rows = [geomint_to_tolerance(m, periods, tol)
            for m in ("yoshida-6", "blanes-moan-6", "kahan-li-8", "sofroniou-spaletta-10")]
    for m in ("RK45", "DOP853", "Radau"):
        rows.append(scipy_to_tolerance(m, periods, tol, budget))
    out["kepler_to_1e-8"] = {"periods": periods, "e": 0.6, "tolerance": tol, "rows": rows}
    for r in rows:
        s = f"{r['seconds']:.3f} s" if r["seconds"] is not None else r.get("note", "-")
        print(f"{r['solver']:32s} {s:>12s}  error {r['error']:.2e}  "
              f"{r.get('force_evals', 0)} force evaluations")
    g = [r["seconds"] for r in rows if r["solver"].startswith("geomint") and r["seconds"]]
    s = [r["seconds"] for r in rows if r["solver"].startswith("scipy") and r["seconds"]]
    if g and s:
        out["best_ratio"] = min(g) / min(s)
        print(f"geomint best / SciPy best: {out['best_ratio']:.3f}")
    return out


if __name__ == "__main__":
    main()
