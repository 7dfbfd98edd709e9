#!/usr/bin/env python3
"""The tank's pressure one frame at a time: for each recorded frame (`ranryu record --export-particles
ply`, the pressure of each frame's last step), the mean over the interior layers' particles of
p - rho0 g (H - z), in % of rho0 g H; then their mean, standard deviation and lag-1 autocorrelation.
Usage: frame_offsets.py FOLDER DX [FIRST_FRAME [H]] (H default 0.25 m, rho0 1000, g 9.81). Interior: the
layers a kernel support (2 DX) from the floor and from H, as `validate hydrostatic` compares."""
import glob
import math
import os
import struct
import sys

folder, dx = sys.argv[1], float(sys.argv[2])
first = int(sys.argv[3]) if len(sys.argv) > 3 else 20
height = float(sys.argv[4]) if len(sys.argv) > 4 else 0.25
scale = 1000.0 * 9.81 * height
offsets = []
for path in sorted(glob.glob(os.path.join(folder, "particles_*.ply"))):
    if int(path[-9:-4]) < first:
        continue
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    n = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    names = [l.split()[2] for l in header if l.startswith("property")]
    fmt = "<" + "f" * len(names)
    stride = struct.calcsize(fmt)
    total, count = 0.0, 0
    for k in range(n):
        rec = dict(zip(names, struct.unpack_from(fmt, data, end + k * stride)))
        layer = math.floor(rec["y"] / dx)
        z = (layer + 0.5) * dx
        if 2 * dx < z < height - 2 * dx:
            total += rec["pressure"] - 1000.0 * 9.81 * (height - z)
            count += 1
    offsets.append(100.0 * total / count / scale)
m = sum(offsets) / len(offsets)
var = sum((o - m) ** 2 for o in offsets) / len(offsets)
ac = sum((offsets[i] - m) * (offsets[i + 1] - m) for i in range(len(offsets) - 1)) / (var * len(offsets))
print(f"{folder}: frames {first}-{first + len(offsets) - 1}: the interior's offset a frame, mean {m:+.2f} %, "
      f"sd {math.sqrt(var):.2f} %, lag-1 autocorrelation {ac:.2f} (of rho0 g H)")
print(" ".join(f"{o:+.1f}" for o in offsets))
