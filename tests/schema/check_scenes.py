#!/usr/bin/env python3
"""media/scenes/scene.schema.json against a real JSON Schema validator (python3-jsonschema): the schema
is valid draft 2020-12, every bundled scene and every validation case's scene (media/validation/*.json)
satisfies it, and the test scenes with an unknown key or a
value out of range do not. Exit 77 (CTest: skipped) where the module is missing."""
import glob
import json
import os
import sys

try:
    import jsonschema
except ImportError:
    print("python3-jsonschema is not installed (scripts/install-deps.sh installs it); skipping")
    sys.exit(77)

root = sys.argv[1]
schema = json.load(open(os.path.join(root, "media/scenes/scene.schema.json")))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
failed = False
scenes = sorted(f for f in glob.glob(os.path.join(root, "media/scenes/*.json")) if not f.endswith(".schema.json"))
scenes += sorted(glob.glob(os.path.join(root, "media/validation/*.json")))
for path in scenes:
    for e in validator.iter_errors(json.load(open(path))):
        print(f"{path}: {'/'.join(map(str, e.path))}: {e.message}")
        failed = True
for name in ("unknown-key.json", "out-of-range.json"):
    path = os.path.join(root, "tests/data/scenes", name)
    if validator.is_valid(json.load(open(path))):
        print(f"{path}: satisfies the schema, but ranryu refuses it")
        failed = True
print(f"{len(scenes)} bundled and validation scenes checked against the schema")
sys.exit(1 if failed or len(scenes) < 5 else 0)
