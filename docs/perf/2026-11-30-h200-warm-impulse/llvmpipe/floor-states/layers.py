# The tank at rest at 0.01 m: each of the six lowest layers' mean height, its scatter, and its mean
# pressure against rho0 g (H - y) in units of rho0 g dx, over frames 60-119 of `ranryu record ...
# --export-particles ply` runs (all particles, and those two spacings or more from the side walls).
#     python3 layers.py OUT_DIR_1 OUT_DIR_2 ...
import sys, glob, numpy as np
def read_ply(f):
    with open(f,'rb') as fh:
        props=[]; n=0
        while True:
            l=fh.readline().decode().strip()
            if l.startswith('element vertex'): n=int(l.split()[-1])
            elif l.startswith('property'):
                _,t,name=l.split(); props.append((name,{'float':'<f4','double':'<f8','uint':'<u4','int':'<i4','uchar':'u1'}[t]))
            elif l=='end_header': break
        return np.frombuffer(fh.read(), dtype=np.dtype(props), count=n)
dx=0.01; H=0.25; rho=1000; g=9.81
for run in sys.argv[1:]:
    files=sorted(glob.glob(f'{run}/particles_*.ply'))[60:]
    acc={}
    for f in files:
        p=read_ply(f)
        y=p['y']; pr=p['pressure'] if 'pressure' in p.dtype.names else None
        x=p['x']; z=p['z']
        inner=(x>2*dx)&(x<0.3-2*dx)&(z>2*dx)&(z<0.1-2*dx)
        for k in range(6):
            m=(y>=k*dx)&(y<(k+1)*dx)
            mi=m&inner
            a=acc.setdefault(k,[[],[],[],[],[]])
            a[0].append(y[m].mean()/dx); a[1].append(y[m].std()/dx); a[2].append(pr[m].mean()); a[3].append(m.sum()); a[4].append(pr[mi].mean() if mi.any() else np.nan)
    print(run, 'frames', len(files), 'fields', p.dtype.names)
    for k in range(6):
        a=acc[k]; ym=np.mean(a[0]); ref=rho*g*(H-ym*dx)
        print(f'  layer {k}: mean y {ym:.3f} dx, std {np.mean(a[1]):.3f} dx, count {np.mean(a[3]):.0f}, p {np.mean(a[2]):.1f} Pa, ref {ref:.1f}, excess {(np.mean(a[2])-ref)/(rho*g*dx):+.3f} rho g dx; inner excess {(np.nanmean(a[4])-ref)/(rho*g*dx):+.3f}')
