#!/usr/bin/python3
"""The impact cases' readings (`ranryu validate impact-pressure|obstacle-impact --json FILE`,
docs/VALIDATION.md "Impact pressure") against their experiments' (Lobovsky et al. 2014; Kleefsman et al.
2005): one panel a sensor, p/(rho0 g H) against T = t sqrt(g/H), the experiment in black and each run in
colour, labelled with its solver, its wall drag (DFSPH's sph.boundary_viscosity) and its H/dx; the
compared window shaded. PNG and SVG (text kept as text).

    scripts/impact-charts.py RUN.json [RUN.json ...] --out PREFIX [--title TEXT]

The runs must be of one case. Writes PREFIX.png and PREFIX.svg. The experiment's series are read from the
repository's media/validation/ (lobovsky_exp_data_pN.csv, kleefsman_exp_data_pN.csv).
"""
import argparse
import csv
import json
import os
import sys

try:
    import matplotlib
except ImportError:
    sys.exit("impact-charts: python3-matplotlib is not installed (scripts/install-deps.sh installs it)")

matplotlib.use("Agg")
matplotlib.rcParams["svg.fonttype"] = "none"   # the SVG's labels stay <text>, readable and searchable
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


CASES = {
    "impact-pressure": ("lobovsky", "The surge's pressure on the wall it strikes, against Lobovsky et al. (2014)",
                        "experiment (Lobovsky et al. 2014)", ("P1", "P3", "P4")),
    "obstacle-impact": ("kleefsman", "The surge's pressure on the box it strikes, against Kleefsman et al. (2005)",
                        "experiment (Kleefsman et al. 2005)", ("P1", "P3")),
}


def well_formed(run):
    """Whether `run` is the JSON of one of CASES with its sensors in order, each with a (T, p) series."""
    if not isinstance(run, dict) or run.get("case") not in CASES or not isinstance(run.get("sensors"), list):
        return False
    names = CASES[run["case"]][3]
    if len(run["sensors"]) != len(names):
        return False
    for sensor, name in zip(run["sensors"], names):
        if not isinstance(sensor, dict) or sensor.get("name") != name or not isinstance(sensor.get("z"), (int, float)):
            return False
        series = sensor.get("simulation")
        if not isinstance(series, list) or not all(isinstance(q, dict) and isinstance(q.get("T"), (int, float)) and
                                                   isinstance(q.get("p"), (int, float)) for q in series):
            return False
    return True


def experiment(case, name):
    path = os.path.join(ROOT, "media", "validation", "%s_exp_data_p%s.csv" % (CASES[case][0], name[1:]))
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
    ap.add_argument("--title", help="the chart's title (default: the case's)")
    args = ap.parse_args()
    runs = []
    for path in args.runs:
        try:
            with open(path) as f:
                run = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit("impact-charts: %s: %s" % (path, e))
        if not well_formed(run):
            sys.exit("impact-charts: %s: not the JSON of `ranryu validate impact-pressure` or `obstacle-impact`" % path)
        if runs and (run["case"] != runs[0]["case"] or len(run["sensors"]) != len(runs[0]["sensors"])):
            sys.exit("impact-charts: %s: a run of %s, where %s is of %s" % (path, run["case"], args.runs[0], runs[0]["case"]))
        runs.append(run)
    case = runs[0]["case"]
    window = runs[0].get("window", [3.0, 5.5])
    n = len(runs[0]["sensors"])
    fig, axes = plt.subplots(n, 1, figsize=(9, 3.4 * n), sharex=True, squeeze=False)
    axes = [a[0] for a in axes]
    for k, ax in enumerate(axes):
        name = runs[0]["sensors"][k]["name"]
        ax.axvspan(window[0], window[1], color="0.92", label="compared window")
        t, p = zip(*experiment(case, name))
        ax.plot(t, p, color="black", linewidth=1.6, label=CASES[case][2])
        for run in runs:
            s = run["sensors"][k]
            ax.plot([q["T"] for q in s["simulation"]], [q["p"] for q in s["simulation"]], linewidth=1.0, label=label(run))
        ax.set_ylabel("p/(rho0 g H)")
        ax.set_title("%s, %.0f mm above the floor" % (name, 1000.0 * runs[0]["sensors"][k]["z"]), fontsize=10)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("T = t sqrt(g/H)")
    axes[0].legend(fontsize=8, loc="upper left")
    fig.suptitle(args.title or CASES[case][1], fontsize=11)
    fig.tight_layout()
    try:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        for ext in ("png", "svg"):
            fig.savefig("%s.%s" % (args.out, ext), dpi=110)
    except OSError as e:
        sys.exit("impact-charts: --out %s: %s" % (args.out, e.strerror or e))
    print("wrote %s.png and %s.svg" % (args.out, args.out))


if __name__ == "__main__":
    main()
