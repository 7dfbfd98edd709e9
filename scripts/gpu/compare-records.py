#!/usr/bin/env python3
"""Compares two `ranryu profile --records` CSV files frame by frame: prints, for each field that differs,
in how many frames it does (the frames both files have).

    python3 scripts/gpu/compare-records.py NEW.csv OLD.csv
"""
import csv
import sys

a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
differ = {}
for ra, rb in zip(a, b):
    for k in ra:
        if ra[k] != rb.get(k):
            differ[k] = differ.get(k, 0) + 1
print(f"records against {sys.argv[2]}: {min(len(a), len(b))} frames ({len(a)} and {len(b)}); fields that differ (frames):",
      differ or "none")
