import csv,sys
for f in sys.argv[1:]:
    rows=list(csv.DictReader(open(f)))
    def agg(a,b):
        R=[r for r in rows if a<=float(r['time'])<=b]
        st=sum(int(r['substeps']) for r in R); it=sum(int(r['iterations']) for r in R)
        return f"{st/len(R):5.2f} st/fr {it/st:5.2f} it/st {it/len(R):6.1f} it/fr maxrho {max(float(r['max_density']) for r in R):.3f}"
    print(f, "| 0-2s", agg(0,2), "| 4-10s", agg(4,10.1), "| all", agg(0,10.1), "unconv", sum(int(r['unconverged']) for r in rows))
