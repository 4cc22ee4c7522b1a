"""Plots with matplotlib (the Agg backend unless one is chosen): energy error of runs,
work–precision diagrams, field snapshots. Each function returns the matplotlib Figure and,
given `path`, saves it there."""
import matplotlib

if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "ps", "cairo"):
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def _finish(fig, path):
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def energy_error(*results, path=None, labels=None):
    """Relative energy error |H - H0|/|H0| against time of one or more Results (log scale)."""
    fig, ax = plt.subplots(figsize=(6, 3.6))
    for i, r in enumerate(results):
        err = r.rel_energy_error()
        label = labels[i] if labels else r.method
        ax.semilogy(r.t[1:], np.maximum(err[1:], 1e-17), label=label)
    ax.set_xlabel("t")
    ax.set_ylabel("relative energy error")
    ax.legend()
    return _finish(fig, path)


def work_precision(rows, path=None, cost="force_evals"):
    """rows: {label: (costs, errors)}, or the result of geomint.work_precision (then `cost`
    picks "force_evals", "seconds" or "steps"); log–log lines, one per label."""
    fig, ax = plt.subplots(figsize=(6, 4))
    for label, row in rows.items():
        c, err = (row[cost], row["error"]) if isinstance(row, dict) else row
        ax.loglog(c, err, "o-", label=label)
    ax.set_xlabel(cost.replace("_", " ") if any(isinstance(r, dict) for r in rows.values())
                  else "cost")
    ax.set_ylabel("error")
    ax.legend()
    return _finish(fig, path)


def field(scene, component, path=None, k=0):
    """A 2-D slice (index k along z) of a field component of a yee.Scene."""
    f = scene.field(component)[k]
    g = scene.grid
    fig, ax = plt.subplots(figsize=(6, 4.5))
    m = np.max(np.abs(f)) or 1.0
    extent = [g["origin"][0], g["origin"][0] + g["n"][0] * g["h"][0],
              g["origin"][1], g["origin"][1] + g["n"][1] * g["h"][1]]
    im = ax.imshow(f, origin="lower", cmap="RdBu_r", vmin=-m, vmax=m, extent=extent)
    fig.colorbar(im, ax=ax, label=component)
    ax.set_title(f"{component} at t = {scene.time:.3g}")
    return _finish(fig, path)


def trajectory(result, path=None):
    """q2 against q1 of a run (orbits)."""
    fig, ax = plt.subplots(figsize=(4.5, 4.5))
    ax.plot(result.q[:, 0], result.q[:, 1], lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("q1")
    ax.set_ylabel("q2")
    return _finish(fig, path)
