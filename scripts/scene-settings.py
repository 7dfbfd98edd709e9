#!/usr/bin/python3
"""Choose each bundled scene's solver and time-step setting from a `ranryu sweep` of its scene case:
the cheapest setting that held together for the whole run with little compression (the rule of
docs/SWEEP.md "Choosing a scene's settings", stated again below). Standard library only.

    scripts/scene-settings.py SWEEP [SWEEP ...] [--at-scale SWEEP ...] [--max-compression 0.01]
                              [--max-density 1.3] [--seconds 10] [--json FILE]

A SWEEP is a sweep.json or the folder `ranryu sweep --out` wrote it to; several (shards) are merged,
a row seen twice counting once. Only the scene cases' rows (case "scene:NAME") are read. For each
scene and spacing it prints the chosen row, the keys to merge into the scene file's "sph" object
(with a "why" saying what chose them) and every row's verdict; --json FILE writes the same as JSON.

The rule. A row is sound when
  1. its status is "stable": the guard fired in no frame, and where the row's energy_check applies
     (no turbulence force) the fluid did not gain more than 1 % of its energy (app/sweep.cpp);
  2. it ran at least --seconds of simulated time (its "seconds" and its "simulated_seconds");
  3. its mean_density_deviation_peak, the largest over its frames of the mean over particles of
     max(rho/rho0 - 1, 0), is at most --max-compression (PBF's densities are those after its last
     iteration, as the guard reads them: its compression counts like the others');
  4. its largest density in any frame, 1 + max_density_deviation, is at most --max-density (default
     1.3 rho0: a margin of 0.2 rho0 to the guard's bound of 1.5, which a scene must never reach).
A row is eligible when it is sound, every row of the same scene, spacing and solver at a smaller
time-step factor is sound too (a stable setting above an unstable one is luck, not a margin), and a
scene file can hold its settings (each within the bounds of media/scenes/scene.schema.json), and,
with --at-scale, the same scene, solver and factor is sound at every other spacing those sweeps hold
for the scene too (the sizes the scene is run at, e.g. about 250k and 1M particles): a row with no
such row at one of them is not eligible either ("not run at ..."; a scene with no rows there at all is
chosen as without them, and said to be unchecked). A step that holds at a scene's few
thousand particles need not at a million (docs/SWEEP.md "The scene settings again, on the H200").
The chosen row is the eligible row of least cost: gpu_ms_per_simulated_second where every row of the
scene and spacing was timed on a GPU (not llvmpipe, softpipe or swrast, and a positive time), else
steps per simulated second (timings from a software renderer say nothing of a GPU); ties go to the
smaller max_density_deviation, then to the key. A scene none of whose rows is eligible gets no choice
(said so, exit code 0). Exit code 2, with one line on stderr, for input that is not a sweep's rows.
"""
import argparse
import json
import os
import sys
from collections import namedtuple

import sweep_rows  # scripts/sweep_rows.py, beside this file

SOFTWARE = ("llvmpipe", "softpipe", "swrast")
REQUIRED = ("key", "case", "solver", "spacing", "factor", "status")


def fail(message):
    print(f"scene-settings: {message}", file=sys.stderr)
    sys.exit(2)


def load(paths):
    try:
        return sweep_rows.load(paths, REQUIRED)
    except sweep_rows.NotRows as e:
        fail(str(e))


class OneLineParser(argparse.ArgumentParser):
    """Bad arguments as one line on stderr and exit code 2, as ranryu reports bad input."""

    def error(self, message):
        fail(message)


# The step's bounds a factor scales (app/sweep.cpp); DFSPH's sph.dfsph_cfl too where a row carries it.
STEP_KEYS = ("cfl", "force_factor", "max_time_step")


def bounds(schema_path):
    """The sph keys a choice sets, with their (minimum, maximum) from the scene schema."""
    try:
        with open(schema_path) as f:
            sph = json.load(f)["properties"]["sph"]["properties"]
    except (OSError, ValueError, KeyError, TypeError) as e:
        fail(f"{schema_path}: not the scene schema ({e})")
    out = {k: (sph[k]["minimum"], sph[k]["maximum"]) for k in STEP_KEYS + ("dfsph_cfl",)}
    for k in ("substeps", "iterations"):
        p = sph["pbf"]["properties"][k]
        out["pbf." + k] = (p["minimum"], p["maximum"])
    return out


def short(x):
    """A float32 the sweep wrote as a double (0.6000000238418579), as the scene file should say it."""
    return float(f"{x:.6g}")


def step_keys(row):
    """The step's keys a row of WCSPH or DFSPH ran with: for DFSPH where its scene sets sph.dfsph_cfl,
    that in place of cfl (which only WCSPH's step then reads)."""
    if "dfsph_cfl" in row:
        return ("dfsph_cfl",) + STEP_KEYS[1:]
    return STEP_KEYS


def settings(row):
    """The keys of the scene's "sph" object that give this row's setting."""
    s = {"solver": row["solver"]}
    if row["solver"] == "pbf":
        s["pbf"] = {"substeps": row["pbf_substeps"], "iterations": row["pbf_iterations"]}
    elif row["factor"] != 1:
        for k in step_keys(row):
            s[k] = short(row[k])
    return s


def out_of_bounds(row, limits):
    """Why a scene file cannot hold this row's setting, or None."""
    if row["solver"] == "pbf":
        values = {"pbf.substeps": row.get("pbf_substeps"), "pbf.iterations": row.get("pbf_iterations")}
    else:
        values = {k: row.get(k) for k in step_keys(row)}
    for k, v in values.items():
        if v is None:
            return f"the row lacks {k}"
        lo, hi = limits[k]
        if not lo <= short(v) <= hi:
            return f"sph.{k} = {short(v):g} is outside the scene key's bounds [{lo:g}, {hi:g}]"
    return None


# The thresholds of rules 2-4: simulated seconds, mean compression and largest density (a fraction, rho0).
Rule = namedtuple("Rule", "seconds max_compression max_density")


def soundness(row, rule):
    """Why the row is not sound (rules 1-4), or None."""
    seconds, max_compression = rule.seconds, rule.max_compression
    if row["status"] != "stable":
        return f"unstable: {row.get('failure_message') or row.get('failure_cause') or '?'}"
    if row.get("seconds", 0) < seconds * (1 - 1e-6) or row.get("simulated_seconds", 0) < seconds * 0.999:
        return f"ran {row.get('simulated_seconds', 0):g} s of the {seconds:g} s asked"
    peak = row.get("mean_density_deviation_peak")
    if peak is None:
        return "no mean_density_deviation_peak (not a scene case's row)"
    if peak > max_compression:
        return f"mean compression reached {100 * peak:.3g} % (t = {row.get('mean_density_deviation_peak_time', 0):.2f} s) > {100 * max_compression:g} %"
    if row.get("max_density_deviation") is None:
        return "no max_density_deviation (not a scene case's row)"
    largest = 1 + row["max_density_deviation"]
    if largest > rule.max_density:
        return f"largest density {largest:.3g} rho0 > {rule.max_density:g} rho0"
    return None


def num(x):
    """A cost as the report shows it: whole above 100, else three digits."""
    return f"{x:.0f}" if x >= 100 else f"{x:.3g}"


def own_spacing(scene, scenes_dir):
    """The spacing the scene's file ships with (media/scenes/NAME.json), or None where it is not found."""
    try:
        with open(os.path.join(scenes_dir, scene + ".json")) as f:
            return float(json.load(f)["particles"]["spacing"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def label(row):
    if row["solver"] == "pbf":
        return f"pbf x{row['factor']:g} ({row.get('pbf_substeps')}x{row.get('pbf_iterations')})"
    return f"{row['solver']} x{row['factor']:g}"


def setting_key(row):
    """A row's setting across spacings: its solver and factor (rounded, as sweeps may store it through a float)."""
    return row["solver"], round(float(row["factor"]), 6)


def other_sizes(row, scale):
    """(spacing, the row's setting there or None) for each spacing of the --at-scale rows `scale`
    ({spacing: {(solver, factor): row}}) other than the row's own, coarsest first."""
    for spacing, at in sorted(scale.items(), reverse=True):
        if abs(spacing - row["spacing"]) > 1e-6 * spacing:
            yield spacing, at.get(setting_key(row))


def at_scale_verdict(row, scale, rule):
    """Why the row's setting (its solver and factor) does not hold at the scene's other sizes, or None."""
    for spacing, other in other_sizes(row, scale):
        if other is None:
            return f"not run at {spacing:g} m (the --at-scale rows' spacing for this scene)"
        why_not = soundness(other, rule)
        if why_not is not None:
            return f"at {spacing:g} m ({other.get('particles', '?')} particles): {why_not}"
    return None


def scale_spacings(row, scale):
    """The --at-scale sizes a chosen row held at, for its "why": "0.00454 m (244088 particles)", ..."""
    return [f"{spacing:g} m ({other.get('particles', '?')} particles)" for spacing, other in other_sizes(row, scale)
            if other is not None]


def choose(rows, rule, limits, scenes_dir, scale_rows=()):
    """Per (scene case, spacing): the verdict on every row and the chosen one. scale_rows: the
    --at-scale rows, each scene's other sizes its rows must hold at too."""
    groups = {}
    for r in rows:
        if str(r["case"]).startswith("scene:"):
            groups.setdefault((r["case"], r["spacing"]), []).append(r)
    scales = {}
    for r in scale_rows:
        if str(r["case"]).startswith("scene:"):
            scales.setdefault(r["case"], {}).setdefault(r["spacing"], {})[setting_key(r)] = r
    results = []
    for (case, spacing), mine in sorted(groups.items()):
        # Timed on a GPU: no row ran on a software renderer, and every row that ran to the end has a time.
        timed = (not any(s in str(r.get("device", "")).lower() for r in mine for s in SOFTWARE) and
                 all(r.get("gpu_ms_per_simulated_second", 0) > 0 for r in mine if r["status"] == "stable"))
        measure = "gpu_ms_per_simulated_second" if timed else "steps"

        def cost(r):
            if r["status"] != "stable":
                return float("inf")
            if timed:
                return r.get("gpu_ms_per_simulated_second", float("inf"))
            return r.get("steps", 0) / max(r.get("simulated_seconds", 0), 1e-9)

        verdicts = {}
        for r in mine:
            why_not = soundness(r, rule)
            if why_not is None:
                worse = [o for o in mine if o["solver"] == r["solver"] and o["factor"] < r["factor"] and
                         soundness(o, rule) is not None]
                if worse:
                    why_not = f"a smaller factor, x{min(o['factor'] for o in worse):g}, is not sound"
            if why_not is None:
                why_not = out_of_bounds(r, limits)
            if why_not is None:
                why_not = at_scale_verdict(r, scales.get(case, {}), rule)
            verdicts[r["key"]] = why_not
        eligible = sorted((r for r in mine if verdicts[r["key"]] is None),
                          key=lambda r: (cost(r), r.get("max_density_deviation", 0), r["key"]))
        chosen = eligible[0] if eligible else None
        scene = case[len("scene:"):]
        own = own_spacing(scene, scenes_dir)
        result = {"case": case, "scene": scene, "spacing": spacing, "cost_measure": measure, "scene_spacing": own,
                  "at_scale": sorted((x for x in scales.get(case, {}) if abs(x - spacing) > 1e-6 * x), reverse=True),
                  "own_spacing": own is None or abs(own - spacing) <= 1e-6 * own,
                  "rows": [{"key": r["key"], "setting": label(r), "cost": cost(r) if r["status"] == "stable" else None,
                            "eligible": verdicts[r["key"]] is None, "why_not": verdicts[r["key"]]}
                           for r in sorted(mine, key=lambda r: (cost(r), r["key"]))]}
        if chosen:
            s = settings(chosen)
            runner_up = next((r for r in eligible[1:] if r["solver"] != chosen["solver"] or r["factor"] != chosen["factor"]), None)
            unit = "GPU ms" if timed else "steps"
            device = str(chosen.get("device", "?")).split(" | ")[0]
            tried = f"the cheapest of the {len(mine)} settings tried that ran" if len(mine) > 1 else "the only setting tried; it ran"
            why = (f"Chosen by scripts/scene-settings.py from ranryu sweep rows ({device}, {str(chosen.get('date', '?'))[:10]}, "
                   f"spacing {spacing:g}): {tried} {rule.seconds:g} s stable with a mean "
                   f"compression of at most {100 * rule.max_compression:g} % in every frame (here {100 * chosen['mean_density_deviation_peak']:.2g} %) "
                   f"and no density above {rule.max_density:g} rho0, "
                   f"{num(cost(chosen))} {unit} a simulated second")
            if runner_up:
                why += f" against {num(cost(runner_up))} for {label(runner_up)}"
            elif len(mine) > 1:
                why += ", the only one eligible"
            held = scale_spacings(chosen, scales.get(case, {}))
            if held:
                why += f", and that held as well at {' and '.join(held)}"
            why += " (the rule: docs/SWEEP.md, Choosing a scene's settings)."
            s["why"] = why
            result.update({"chosen": chosen["key"], "setting": label(chosen), "cost": cost(chosen),
                           "mean_density_deviation_peak": chosen["mean_density_deviation_peak"],
                           "max_density_deviation": chosen.get("max_density_deviation"), "sph": s})
        else:
            result.update({"chosen": None, "sph": None})
        results.append(result)
    return results


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = OneLineParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweeps", nargs="+", help="sweep.json files of ranryu sweep, or the folders holding them")
    ap.add_argument("--at-scale", nargs="+", action="extend", default=[], metavar="SWEEP",
                    help="sweeps of the same scene cases at other spacings (the sizes the scenes are run at): "
                         "a setting is eligible only if it is sound there too")
    ap.add_argument("--max-compression", type=float, default=0.01,
                    help="the largest mean compression allowed in any frame, a fraction of rho0 (default 0.01: 1 %%)")
    ap.add_argument("--max-density", type=float, default=1.3,
                    help="the largest density allowed in any frame, in rho0 (default 1.3: 0.2 below the guard's 1.5)")
    ap.add_argument("--seconds", type=float, default=10.0, help="the simulated seconds a row must have run (default 10)")
    ap.add_argument("--schema", default=os.path.join(here, "..", "media", "scenes", "scene.schema.json"),
                    help="the scene schema, for the bounds of the keys a choice sets")
    ap.add_argument("--scenes", default=os.path.join(here, "..", "media", "scenes"),
                    help="the folder of the scene files, for each scene's own spacing")
    ap.add_argument("--json", help="also write the choices as JSON to this file")
    a = ap.parse_args()
    if not 0 < a.max_compression < 1:
        fail(f"--max-compression {a.max_compression:g}: expected a fraction in (0, 1)")
    if not a.seconds > 0:
        fail(f"--seconds {a.seconds:g}: expected a positive time")
    if not a.max_density > 1:
        fail(f"--max-density {a.max_density:g}: expected a density above 1 (in rho0)")
    results = choose(load(a.sweeps), Rule(a.seconds, a.max_compression, a.max_density), bounds(a.schema), a.scenes,
                     load(a.at_scale) if a.at_scale else ())
    if not results:
        fail("no scene case's rows in " + ", ".join(a.sweeps) + " (run ranryu sweep --cases scenes)")
    for r in results:
        scale = f"; each setting checked at {', '.join(f'{x:g}' for x in r['at_scale'])} m as well" if r["at_scale"] else ""
        if a.at_scale and not r["at_scale"]:
            scale = "; not checked at other sizes: --at-scale holds no rows of this scene"
        print(f"{r['scene']} at spacing {r['spacing']:g} (cost: {r['cost_measure']}{scale}):")
        unit = "GPU ms" if r["cost_measure"] == "gpu_ms_per_simulated_second" else "steps"
        if r["chosen"]:
            print(f"  chosen: {r['setting']}, {num(r['cost'])} {unit} a simulated second, largest mean compression "
                  f"{100 * r['mean_density_deviation_peak']:.3g} %")
            where = f"media/scenes/{r['scene']}.json's \"sph\""
            if not r["own_spacing"]:
                where = (f"{where} only if its spacing becomes {r['spacing']:g} (the file's is {r['scene_spacing']:g}, and the "
                         f"setting was chosen at this one)")
            print(f"  merge into {where}: {json.dumps(r['sph'], ensure_ascii=False)}")
        else:
            print(f"  no setting is eligible (rule: docs/SWEEP.md \"Choosing a scene's settings\"); keep the scene's")
        for row in r["rows"]:
            cost = num(row["cost"]) if row["cost"] is not None else "-"
            print(f"    {row['setting']:22} {cost:>10}  {'eligible' if row['eligible'] else row['why_not']}")
    if a.json:
        try:
            with open(a.json, "w") as f:
                json.dump({"max_compression": a.max_compression, "max_density": a.max_density, "seconds": a.seconds,
                           "scenes": results}, f, indent=1, ensure_ascii=False)
                f.write("\n")
        except OSError as e:
            fail(f"--json {a.json}: {e}")


if __name__ == "__main__":
    main()
