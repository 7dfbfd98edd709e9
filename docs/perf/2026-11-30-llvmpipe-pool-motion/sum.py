import csv, sys, statistics as st
for f in sys.argv[1:]:
    r=list(csv.DictReader(open(f)))
    n=len(r); tail=r[n//3:]
    S=sum(int(x['substeps']) for x in tail); I=sum(int(x['iterations']) for x in tail)
    vm=[float(x['max_speed']) for x in tail]
    print(f"{f}: frames {n}, last 2/3: steps/frame {S/len(tail):.2f}, it/step {I/S:.2f}, it/frame {I/len(tail):.1f}, vmax median {st.median(vm):.3f} max {max(vm):.3f}, rho max {max(float(x['max_density']) for x in tail):.3f}, min_dt med {st.median(float(x['min_dt']) for x in tail)*1e3:.2f} ms")
