# The block's particles at a frame's end, by region: python3 snapshot.py DIR FRAME... (DIR from
#     ranryu record --scene pool.json --frames 64 --export-particles ply --out DIR --size 32x18 --shading particles
import sys
import numpy as np

def load(f):
    b = open(f, 'rb').read()
    i = b.index(b'end_header\n') + len('end_header\n')
    return np.frombuffer(b[i:], dtype='<f4').reshape(-1, 8)   # x y z vx vy vz density pressure

dx = 0.0025
for fr in sys.argv[2:]:
    a = load(f'{sys.argv[1]}/particles_{int(fr):05d}.ply')
    x, s = a[:, :3], np.linalg.norm(a[:, 3:6], axis=1)
    xw, zw, top = np.minimum(x[:, 0], 0.1 - x[:, 0]), np.minimum(x[:, 2], 0.02 - x[:, 2]), x[:, 1].max()
    print(f'frame {fr}: rms {np.sqrt((s ** 2).mean()):.4f} m/s, largest {s.max():.3f}')
    for name, m in [('within dx of the x walls', xw < dx), ('within dx of the z walls', zw < dx),
                    ('the floor layer', x[:, 1] < dx), ('the top 1.5 dx', x[:, 1] > top - 1.5 * dx),
                    ('2 dx from every wall and the surface', (xw > 2 * dx) & (zw > 2 * dx) & (x[:, 1] > 2 * dx) & (x[:, 1] < top - 2 * dx))]:
        print(f'  {name:38s} {m.sum():5d} particles, rms {np.sqrt((s[m] ** 2).mean()):.4f}, largest {s[m].max():.3f}')
