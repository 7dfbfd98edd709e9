# The dam break's ten seconds by phase, from the records in each call's eta-*.tgz:
#     for t in call*/eta-*.tgz; do v=$(basename $t .tgz); mkdir -p /tmp/rx/${v#eta-}; tar xzf $t -C /tmp/rx/${v#eta-}; done
#     python3 phases.py /tmp/rx
import csv, statistics as st, sys
root = sys.argv[1]
for n in ['250000', '1000000']:
    for v in ['ship', 'ext', 'ext2', 'pull', 'tan']:
        r = list(csv.DictReader(open(f'{root}/{v}/eta/db-{n}-1e-3.csv')))
        def phase(a, b):
            t = r[a:b]
            s = sum(int(x['substeps']) for x in t)
            i = sum(int(x['iterations']) for x in t)
            return f'{s / len(t):5.1f} steps/frame {i / s:5.2f} it/step'
        late = r[240:]
        print(n, f'{v:5s}', '0-2 s', phase(0, 120), '| 4-10 s', phase(240, 600),
              f'| fastest, median frame {st.median(float(x["max_speed"]) for x in late):.3f} m/s',
              f'largest rho/rho0 {max(float(x["max_density"]) for x in late):.3f}',
              '| steps at the cap', sum(int(x['unconverged']) for x in r))
