#!/usr/bin/env python3
"""A bundled scene at about N particles, with keys changed, for the scripts of scripts/gpu/.

    scripts/gpu/scene-at.py NAME OUT N [KEY=VALUE ...]

Writes media/scenes/NAME.json to OUT with each KEY (dotted, e.g. sph.pbf.substeps) set to VALUE (read
as JSON where it parses, else a string), and prints the spacing that fills the scene's blocks with
about N particles: (their volume / N)^(1/3), for `ranryu ... --spacing`.
"""
import json
import sys


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    name, out, n = argv[1], argv[2], float(argv[3])
    scene = json.load(open(f"media/scenes/{name}.json"))
    scene.pop("$schema", None)
    for item in argv[4:]:
        key, _, text = item.partition("=")
        try:
            value = json.loads(text)
        except json.JSONDecodeError:
            value = text
        node = scene
        *path, last = key.split(".")
        for part in path:
            node = node.setdefault(part, {})
        node[last] = value
    json.dump(scene, open(out, "w"), indent=1)
    volume = 0.0
    for b in scene["particles"]["blocks"]:
        lo, hi = b.get("min", [0, 0, 0]), b["max"]
        volume += (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
    print(f"{(volume / n) ** (1 / 3):.5f}")


if __name__ == "__main__":
    main(sys.argv)
