#!/usr/bin/env python3
"""MEEP on the benchmark cavity of bench/yee_throughput.c: N^3 vacuum cells, PEC walls, a fixed
number of time steps, measured with 1 MPI process and with `mpirun -np 2` when that is possible.

    bench/meep_cavity.py [--n 128] [--steps 200] [--repeats 3]

Prints a table and, last, one line `MEEP_RESULT {json}` that bench/yee_throughput.c parses:
{"n": N, "steps": S, "runs": [{"np": 1, "seconds": ..., "mcells_steps_per_s": ...}, ...],
"skipped": [reasons]}. Only the time-stepping loop is timed (fields.step(), after init_sim()
and one untimed step), not the set-up: `repeats` loops of `steps` steps on one simulation, the
fastest counts. OMP_NUM_THREADS=1 so that each process uses one core.

MEEP comes from Debian: python3-meep-openmpi (the MPI build; it runs as one process too, and
python3-meep, the serial build, conflicts with it). When `import meep` fails the script installs
it with apt-get (as root), otherwise it prints why it skips and exits 0 with an empty result.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

SYSTEM_PYTHON = "/usr/bin/python3"  # Debian's python, where python3-meep-* installs meep
PACKAGES = ["python3-meep-openmpi", "python3-mpi4py", "python3-matplotlib", "openmpi-bin"]


def worker(n, steps, repeats):
    """One timed run; prints `WORKER {json}` from rank 0."""
    import meep as mp

    mp.verbosity(0)
    # resolution 1 and cell size n: n pixels per axis. No boundary_layers: MEEP's default
    # boundary is a perfect electric conductor. Three point dipoles (Ex, Ey, Ez) off the
    # symmetry planes excite all six components, so MEEP cannot skip any of them.
    c = n / 2.0
    src = mp.GaussianSource(frequency=0.15, fwidth=0.1)
    sources = [
        mp.Source(src, component=mp.Ex, center=mp.Vector3(0.17 * n - c, 0.31 * n - c, 0.23 * n - c)),
        mp.Source(src, component=mp.Ey, center=mp.Vector3(0.61 * n - c, 0.19 * n - c, 0.43 * n - c)),
        mp.Source(src, component=mp.Ez, center=mp.Vector3(0.37 * n - c, 0.71 * n - c, 0.59 * n - c)),
    ]
    sim = mp.Simulation(cell_size=mp.Vector3(n, n, n), resolution=1, sources=sources,
                        eps_averaging=False, dimensions=3)
    sim.init_sim()
    sim.fields.step()  # first step outside the timing: allocations MEEP makes lazily
    seconds = float("inf")
    for _ in range(repeats):
        mp.all_wait()
        t0 = time.perf_counter()
        for _ in range(steps):
            sim.fields.step()
        mp.all_wait()
        seconds = min(seconds, time.perf_counter() - t0)
    if mp.am_master():
        cells = n ** 3
        print("WORKER " + json.dumps({
            "np": mp.count_processors(), "n": n, "steps": steps, "seconds": seconds,
            "mcells_steps_per_s": cells * steps / seconds / 1e6,
            "courant": sim.Courant}), flush=True)


def find_meep_python():
    """A python that imports meep (installing it when we can), or (None, reason)."""
    for py in [sys.executable, SYSTEM_PYTHON]:
        if py and os.path.exists(py) and subprocess.run(
                [py, "-c", "import meep"], capture_output=True).returncode == 0:
            return py, None
    if os.geteuid() != 0 or shutil.which("apt-get") is None:
        return None, "meep is not installed and this is not a root Debian shell: " \
                     "apt-get install " + " ".join(PACKAGES)
    print("meep_cavity: installing " + " ".join(PACKAGES), file=sys.stderr, flush=True)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    r = subprocess.run(["apt-get", "install", "-y", "-q", "--no-install-recommends"] + PACKAGES,
                       env=env, capture_output=True, text=True)
    if r.returncode != 0:
        # The package lists may be missing on a fresh machine: update once and retry.
        subprocess.run(["apt-get", "update", "-q"], env=env, capture_output=True)
        r = subprocess.run(["apt-get", "install", "-y", "-q", "--no-install-recommends"] + PACKAGES,
                           env=env, capture_output=True, text=True)
    if r.returncode != 0:
        tail = (r.stderr.strip().splitlines() or ["?"])[-1]
        return None, "apt-get install " + " ".join(PACKAGES) + " failed: " + tail
    if subprocess.run([SYSTEM_PYTHON, "-c", "import meep"], capture_output=True).returncode == 0:
        return SYSTEM_PYTHON, None
    return None, "meep installed but `import meep` still fails"


def run_worker(cmd, env):
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if line.startswith("WORKER "):
            return json.loads(line[len("WORKER "):]), None
    err = (r.stderr.strip().splitlines() or ["no output"])[-1]
    return None, "%s exited %d: %s" % (" ".join(cmd[:3]), r.returncode, err)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=128, help="cells per axis (default 128)")
    ap.add_argument("--steps", type=int, default=200, help="time steps (default 200)")
    ap.add_argument("--repeats", type=int, default=3, help="timed loops, best counts (default 3)")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.n < 4 or args.steps < 1 or args.repeats < 1:
        ap.error("--n must be >= 4, --steps and --repeats >= 1")
    if args.worker:
        worker(args.n, args.steps, args.repeats)
        return 0

    result = {"n": args.n, "steps": args.steps, "runs": [], "skipped": []}
    py, why = find_meep_python()
    if py is None:
        result["skipped"].append(why)
        print("meep_cavity: skipped: " + why)
        print("MEEP_RESULT " + json.dumps(result), flush=True)
        return 0
    me = os.path.abspath(__file__)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_btl_vader_single_copy_mechanism="none")
    base = [py, me, "--worker", "--n", str(args.n), "--steps", str(args.steps),
            "--repeats", str(args.repeats)]
    run, why = run_worker(base, env)
    if run is not None:
        result["runs"].append(run)
    else:
        result["skipped"].append("np 1: " + why)
    with_mpi = subprocess.run([py, "-c", "import meep,sys; sys.exit(0 if meep.with_mpi() else 1)"],
                              capture_output=True).returncode == 0
    if shutil.which("mpirun") is None:
        result["skipped"].append("np 2: no mpirun on PATH (apt-get install openmpi-bin)")
    elif not with_mpi:
        result["skipped"].append("np 2: the installed meep is the serial build "
                                 "(python3-meep); -np 2 needs python3-meep-openmpi")
    else:
        run, why = run_worker(["mpirun", "-np", "2", "--oversubscribe"] + base, env)
        if run is not None:
            result["runs"].append(run)
        else:
            result["skipped"].append("np 2: " + why)

    print("MEEP %d^3 vacuum cells, PEC, %d steps (Courant 0.5), best of %d"
          % (args.n, args.steps, args.repeats))
    print("%4s %10s %22s" % ("np", "seconds", "Mcells*steps/s"))
    for r in result["runs"]:
        print("%4d %10.3f %22.2f" % (r["np"], r["seconds"], r["mcells_steps_per_s"]))
    for s in result["skipped"]:
        print("skipped: " + s)
    print("MEEP_RESULT " + json.dumps(result), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
