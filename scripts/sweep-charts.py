#!/usr/bin/python3
"""Charts of a `ranryu sweep` (app/sweep.cpp): accuracy against cost with each solver's Pareto front,
one panel a case; and the stability map, one panel a case and solver, spacing against time-step
factor, each cell stable, marked with the guard's cause, or "no result" (ran, but its flow gave no
measurement). PNG and SVG (text kept as text).

    scripts/sweep-charts.py SWEEP [SWEEP ...] --out DIR

A SWEEP is a sweep.json or the folder `ranryu sweep --out` wrote it to. Several (shards of one sweep)
are merged; a row seen twice counts once. Writes
DIR/accuracy-vs-cost.{png,svg} and DIR/stability-map.{png,svg}.
"""
import argparse
import os
import sys
import textwrap

import sweep_rows  # scripts/sweep_rows.py, beside this file

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.fonttype"] = "none"   # the SVG's labels stay <text>, readable and searchable
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"dfsph": "#1f77b4", "wcsph": "#d62728", "pbf": "#2ca02c"}
MARKERS = {"dfsph": "o", "wcsph": "s", "pbf": "^"}
# The guard's criteria (engine/sim/guard.h) and the sweep's own, in a word for a cell.
CAUSES = [("left the domain", "escaped"), ("non-finite", "NaN"), ("density", "density"), ("speed", "speed"),
          ("velocity", "speed"), ("time step", "dt floor"), ("energy", "energy gain"), ("no measurement", "no result")]


def short_cause(cause):
    cause = cause or "?"
    return next((word for key, word in CAUSES if key in cause), cause[:16])


def load(paths):
    try:
        rows = sweep_rows.load(paths)
    except sweep_rows.NotRows as e:
        sys.exit(f"sweep-charts: {e}")
    if not rows:
        sys.exit("sweep-charts: no rows in " + ", ".join(paths))
    return rows


def pareto(points):
    """The points no other point beats in both cost and error, by cost."""
    front, best = [], float("inf")
    for cost, error in sorted(points):
        if error < best:
            front.append((cost, error))
            best = error
    return front


def accuracy_chart(rows, out):
    cases = sorted({r["case"] for r in rows})
    fig, axes = plt.subplots(1, len(cases), figsize=(6 * len(cases), 4.5), squeeze=False)
    for ax, case in zip(axes[0], cases):
        stable = [r for r in rows if r["case"] == case and r.get("status") == "stable"]
        for solver in sorted({r["solver"] for r in stable}):
            mine = [r for r in stable if r["solver"] == solver]
            pts = [(r["gpu_ms_per_simulated_second"], r["error"]) for r in mine]
            c = COLOURS.get(solver, "black")
            ax.scatter(*zip(*pts), color=c, marker=MARKERS.get(solver, "o"), label=f"{solver} runs", alpha=0.7)
            front = pareto(pts)
            ax.plot(*zip(*front), color=c, linestyle="--", label=f"{solver} Pareto front")
            for r in mine:
                ax.annotate(f"dx {r['spacing']:g}, x{r['factor']:g}", (r["gpu_ms_per_simulated_second"], r["error"]),
                            fontsize=6, alpha=0.6, xytext=(3, 3), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_xlabel("cost: GPU ms per simulated second")
        name = next((r.get("error_name") for r in stable if r.get("error_name")), "error")
        # Wrapped at words: the impact cases' names run past the panel's height on one line.
        ax.set_ylabel(textwrap.fill(f"error: {name}", 60), fontsize=8)
        ax.set_title(f"{case}: accuracy against cost")
        ax.grid(True, which="both", alpha=0.3)
        if stable:
            ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, f"accuracy-vs-cost.{ext}"), dpi=120)
    plt.close(fig)


def stability_map(rows, out):
    cases = sorted({r["case"] for r in rows})
    solvers = sorted({r["solver"] for r in rows})
    fig, axes = plt.subplots(len(cases), len(solvers), figsize=(4.4 * len(solvers), 3.4 * len(cases)), squeeze=False)
    for (i, case), (k, solver) in ((c, s) for c in enumerate(cases) for s in enumerate(solvers)):
        ax = axes[i][k]
        mine = [r for r in rows if r["case"] == case and r["solver"] == solver]
        factors = sorted({r["factor"] for r in mine})
        spacings = sorted({r["spacing"] for r in mine})
        for r in mine:
            x, y = factors.index(r["factor"]), spacings.index(r["spacing"])
            ok = r.get("status") == "stable"
            # Green: stable; amber: ran, no measurement ("no result"); red: the guard or the energy.
            colour = "#b7e4c7" if ok else "#ffe08a" if r.get("status") == "no result" else "#f4a6a6"
            ax.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, color=colour))
            frame = r.get("failure_frame")
            text = "stable" if ok else short_cause(r.get("failure_cause")) + (f"\nframe {frame}" if frame is not None else "")
            ax.text(x, y, text, ha="center", va="center", fontsize=8)
        ax.set_xlim(-0.5, max(len(factors), 1) - 0.5)
        ax.set_ylim(-0.5, max(len(spacings), 1) - 0.5)
        ax.set_xticks(range(len(factors)), [f"{f:g}" for f in factors])
        ax.set_yticks(range(len(spacings)), [f"{s:g}" for s in spacings])
        ax.set_xlabel("time-step factor")
        ax.set_ylabel("particle spacing (m)")
        ax.set_title(f"stability: {case}, {solver}", fontsize=10)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, f"stability-map.{ext}"), dpi=120)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweeps", nargs="+", help="sweep.json files of ranryu sweep, or the folders holding them")
    ap.add_argument("--out", required=True, help="folder for the charts")
    a = ap.parse_args()
    rows = load(a.sweeps)
    os.makedirs(a.out, exist_ok=True)
    accuracy_chart(rows, a.out)
    stability_map(rows, a.out)
    print(f"sweep-charts: {len(rows)} rows -> {a.out}/accuracy-vs-cost.{{png,svg}}, {a.out}/stability-map.{{png,svg}}")


if __name__ == "__main__":
    main()
