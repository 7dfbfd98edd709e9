# The settled pool's (4-10 s) density iterations a frame and a second, and c = (iterations a second)·h,
# at the four sizes, from call 1's shipped records and call 5's (extracted as phases.py says, call 5's
# eta-sizes.tgz into ROOT/sizes):  python3 sizes.py ROOT
import csv, statistics as st, sys
root = sys.argv[1]
for v, n, dx in [('sizes', '125000', 0.004), ('ship', '250000', 0.00317), ('sizes', '512000', 0.0025), ('ship', '1000000', 0.002)]:
    t = list(csv.DictReader(open(f'{root}/{v}/eta/db-{n}-1e-3.csv')))[240:]
    s = sum(int(x['substeps']) for x in t)
    i = sum(int(x['iterations']) for x in t)
    per_frame = i / len(t)
    print(n, f'steps/frame {s / len(t):.1f}, iterations/step {i / s:.2f}, iterations/frame {per_frame:.1f}, '
          f'a second {per_frame * 60:.0f}, c {per_frame * 60 * 2 * dx:.1f} m/s, '
          f'fastest (median frame) {st.median(float(x["max_speed"]) for x in t):.3f} m/s')
