"""Reading `ranryu sweep` rows, shared by scripts/sweep-charts.py and scripts/scene-settings.py
(standard library only). A SWEEP is a sweep.json or the folder `ranryu sweep --out` wrote it to;
several (shards) are merged, a row seen twice (by its key) counting once."""
import json
import os


class NotRows(Exception):
    """A path that holds no sweep rows, or a row without the fields the caller requires."""


def load(paths, required=("key",)):
    rows = {}
    for path in paths:
        if os.path.isdir(path):
            path = os.path.join(path, "sweep.json")
        try:
            with open(path) as f:
                data = json.load(f)
        except (OSError, ValueError) as e:
            raise NotRows(f"{path}: not a sweep's rows ({e})")
        if not isinstance(data, dict) or not isinstance(data.get("rows"), list):
            raise NotRows(f"{path}: not a sweep's rows (no \"rows\" array)")
        for i, r in enumerate(data["rows"]):
            missing = [k for k in required if not isinstance(r, dict) or k not in r]
            if missing:
                raise NotRows(f"{path}: row {i} lacks {', '.join(missing)}")
            rows[r["key"]] = r
    return list(rows.values())
