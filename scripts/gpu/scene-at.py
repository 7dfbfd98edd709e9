#!/usr/bin/env python3
"""A bundled scene at about N particles, with keys changed, for the scripts of scripts/gpu/.

    scripts/gpu/scene-at.py [--dividing] NAME OUT N [KEY=VALUE ...]

Writes media/scenes/NAME.json to OUT with each KEY (dotted, e.g. sph.pbf.substeps) set to VALUE (read
as JSON where it parses, else a string), and prints the spacing that fills the scene's blocks with
about N particles: (their volume / N)^(1/3), for `ranryu ... --spacing`.

With --dividing it prints instead the spacing nearest that one which divides every block's extents
exactly (their greatest common divisor over a whole number), so that a block resting against walls
has its lattice half a spacing from each of them: at another spacing the far walls' gaps differ, and
the tank at rest's first frames kick there (docs/DFSPH.md).
"""
import json
import math
import sys


def main(argv):
    dividing = len(argv) > 1 and argv[1] == "--dividing"
    if dividing:
        argv = argv[:1] + argv[2:]
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
    volume, extents = 0.0, []
    for b in scene["particles"]["blocks"]:
        lo, hi = b.get("min", [0, 0, 0]), b["max"]
        volume += (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
        extents += [hi[a] - lo[a] for a in range(3)]
    spacing = (volume / n) ** (1 / 3)
    if not dividing:
        print(f"{spacing:.5f}")
        return
    # The extents in micrometres (scene files give them to a few decimals), their gcd, and the whole
    # number of spacings in it nearest the asked count's spacing.
    unit = 0
    for e in extents:
        unit = math.gcd(unit, round(e * 1e6))
    pitch = unit * 1e-6
    if pitch < 0.5 * spacing:   # the nearest dividing spacing would be far finer than the one asked
        sys.exit(f"scene-at.py --dividing: the blocks of {name} share no divisor near {spacing:.5f} m "
                 f"(the greatest common divisor of their extents is {pitch:.6g} m)")
    k = max(1, round(pitch / spacing))
    print(f"{pitch / k:.10g}")


if __name__ == "__main__":
    main(sys.argv)
