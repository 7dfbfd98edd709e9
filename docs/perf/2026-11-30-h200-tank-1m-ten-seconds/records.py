"""Summarise profile --records CSVs (one run's, or a run's parts in order): frames, time reached, steps a
frame, density iterations a step, the largest density and speed, NaN and escaped counts.
    python3 records.py a.csv [b.csv ...]"""
import csv
import sys

r = [row for name in sys.argv[1:] for row in csv.DictReader(open(name))]
s = sum(float(x["substeps"]) for x in r)
print(f"{len(r)} frames ({r[0]['frame']}..{r[-1]['frame']}), t {float(r[-1]['time']):.3f} s, {s / len(r):.1f} steps/frame, "
      f"{sum(float(x['iterations']) for x in r) / s:.2f} density iterations/step, largest rho/rho0 {max(float(x['max_density']) for x in r):.4f}, "
      f"fastest {max(float(x['max_speed']) for x in r):.2f} m/s, nan {sum(int(x['nan']) for x in r)}, escaped {sum(int(x['escaped']) for x in r)}")
