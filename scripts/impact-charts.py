#!/usr/bin/python3
"""The impact-pressure case's readings (`ranryu validate impact-pressure --json FILE`, docs/VALIDATION.md
"Impact pressure") against Lobovsky et al. (2014)'s: one panel a sensor (P1, P3, P4), p/(rho0 g H) against
T = t sqrt(g/H), the experiment in black and each run in colour, labelled with its solver, its wall
drag (DFSPH's sph.boundary_viscosity) and its H/dx; the compared run-up window shaded. PNG and SVG (text
kept as text).

    scripts/impact-charts.py RUN.json [RUN.json ...] --out PREFIX [--title TEXT]

Writes PREFIX.png and PREFIX.svg. The experiment's series is read from the repository's
media/validation/lobovsky_exp_data_p{1,3,4}.csv.
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.fonttype"] = "none"   # the SVG's labels stay <text>, readable and searchable
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def experiment(name):
    path = os.path.join(ROOT, "media", "validation", "lobovsky_exp_data_p%s.csv" % name[1:])
    with open(path) as f:
        return [(float(t), float(p)) for t, p in (row for row in csv.reader(f) if row and not row[0].startswith("#"))]


def label(run):
    text = run.get("solver", "?")
    if text == "dfsph":
        nu = run.get("boundary_viscosity", 0.0)
        text += ", free-slip" if nu == 0 else ", nu_b %g" % nu
    h, dx = run.get("height"), run.get("spacing")
    if h and dx:
        text += ", H/dx %.0f" % (h / dx)
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+", help="JSON files of `ranryu validate impact-pressure --json`")
    ap.add_argument("--out", required=True, help="PREFIX of PREFIX.png and PREFIX.svg")
    ap.add_argument("--title", default="The surge's pressure on the wall it strikes, against Lobovsky et al. (2014)")
    args = ap.parse_args()
    runs = []
    for path in args.runs:
        try:
            with open(path) as f:
                run = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit("impact-charts: %s: %s" % (path, e))
        if run.get("case") != "impact-pressure" or len(run.get("sensors", [])) != 3:
            sys.exit("impact-charts: %s: not the JSON of `ranryu validate impact-pressure`" % path)
        runs.append(run)
    window = runs[0].get("window", [3.0, 5.5])
    fig, axes = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    for k, ax in enumerate(axes):
        name = runs[0]["sensors"][k]["name"]
        ax.axvspan(window[0], window[1], color="0.92", label="compared run-up")
        t, p = zip(*experiment(name))
        ax.plot(t, p, color="black", linewidth=1.6, label="experiment (Lobovsky et al. 2014)")
        for run in runs:
            s = run["sensors"][k]
            ax.plot([q["T"] for q in s["simulation"]], [q["p"] for q in s["simulation"]], linewidth=1.0, label=label(run))
        ax.set_ylabel("p/(rho0 g H)")
        ax.set_title("%s, %.0f mm above the floor" % (name, 1000.0 * runs[0]["sensors"][k]["z"]), fontsize=10)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("T = t sqrt(g/H)")
    axes[0].legend(fontsize=8, loc="upper left")
    fig.suptitle(args.title, fontsize=11)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig("%s.%s" % (args.out, ext), dpi=110)
    print("wrote %s.png and %s.svg" % (args.out, args.out))


if __name__ == "__main__":
    main()
