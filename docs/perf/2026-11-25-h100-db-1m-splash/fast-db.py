#!/usr/bin/env python3
# Ad-hoc: the fastest particles of dam-break PLY frames: position, velocity, distances to every wall
# and the lid (in spacings), fluid neighbours within 2 dx, density and pressure.
import sys, math, array
sys.path.insert(0, "scripts/gpu")
import importlib.util
spec = importlib.util.spec_from_file_location("fp", "scripts/gpu/fast-particles.py"); fp = importlib.util.module_from_spec(spec); spec.loader.exec_module(fp)
dx = float(sys.argv[1]); lo = [0, 0, 0]; hi = [1.0, 0.5, 0.1]
for path in sys.argv[2:]:
    names, n, get = fp.read_ply(path)
    X = [get(i, "x") for i in range(n)]; Y = [get(i, "y") for i in range(n)]; Z = [get(i, "z") for i in range(n)]
    VX = [get(i, "vx") for i in range(n)]; VY = [get(i, "vy") for i in range(n)]; VZ = [get(i, "vz") for i in range(n)]
    sp = [math.sqrt(a*a+b*b+c*c) for a, b, c in zip(VX, VY, VZ)]
    order = sorted(range(n), key=lambda i: -sp[i])[:10]
    cells = {}
    for i in range(n):
        cells.setdefault((int(X[i]/(2*dx)), int(Y[i]/(2*dx)), int(Z[i]/(2*dx))), []).append(i)
    def nb(i):
        c = (int(X[i]/(2*dx)), int(Y[i]/(2*dx)), int(Z[i]/(2*dx))); k = 0
        for a in (-1,0,1):
            for b in (-1,0,1):
                for d in (-1,0,1):
                    for j in cells.get((c[0]+a, c[1]+b, c[2]+d), []):
                        if j != i and (X[j]-X[i])**2+(Y[j]-Y[i])**2+(Z[j]-Z[i])**2 < (2*dx)**2: k += 1
        return k
    fast = sum(1 for s in sp if s > 6.0)
    print(f"{path}: {n} particles, fastest {sp[order[0]]:.2f} m/s, past 6 m/s: {fast}, mean speed {sum(sp)/n:.2f}")
    print("   speed    vx     vy     vz  |    x      y      z   | -x    +x   floor  lid   -z    +z  | nbrs  rho     p")
    has_rho = "density" in names; has_p = "pressure" in names
    for i in order:
        w = [(X[i]-lo[0])/dx, (hi[0]-X[i])/dx, (Y[i]-lo[1])/dx, (hi[1]-Y[i])/dx, (Z[i]-lo[2])/dx, (hi[2]-Z[i])/dx]
        print(f"  {sp[i]:6.2f} {VX[i]:6.2f} {VY[i]:6.2f} {VZ[i]:6.2f} | {X[i]:.4f} {Y[i]:.4f} {Z[i]:.4f} | "
              + " ".join(f"{d:5.1f}" for d in w) + f" | {nb(i):4d} {get(i,'density') if has_rho else 0:7.1f} {get(i,'pressure') if has_p else 0:8.1f}")
