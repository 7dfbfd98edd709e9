#!/usr/bin/env python3
"""The one-walk DFSPH iteration's acceleration (docs/PERFORMANCE.md "The one-walk iteration's acceleration,
answered"): the best spectral radius, over a grid of (alpha, beta), of the two-step recurrence on a
one-walk-late residual, e_{k+1} = (1 + beta) e_k - (beta + alpha mu) e_{k-1}, against heavy-ball momentum
on the current residual (two walks an iteration), e_{k+1} = (1 + beta - alpha mu) e_k - beta e_{k-1},
for the eigenvalues mu of the preconditioned operator in [1/kappa, 1]; and the walks each needs to
reduce the error a thousandfold."""
import cmath, math
def roots(p,q):  # z^2 + p z + q
    d=cmath.sqrt(p*p-4*q); return ((-p+d)/2,(-p-d)/2)
def rho(kind,a,b,mus):
    r=0
    for mu in mus:
        if kind=='d': z=roots(-(1+b),b+a*mu)
        else: z=roots(-(1+b-a*mu),b)
        r=max(r,abs(z[0]),abs(z[1]))
        if r>=1: return r
    return r
for kappa in [30,100,300,1000]:
    mus=[1/kappa+(1-1/kappa)*i/199 for i in range(200)]
    res={}
    for kind,amax in (('d',1.5),('h',2.5)):
        best=(9,0,0)
        for i in range(60):
            a=0.02+amax*i/59
            for j in range(100):
                b=0.99*j/99
                r=rho(kind,a,b,mus)
                if r<best[0]: best=(r,a,b)
        res[kind]=best
    d,h=res['d'],res['h']
    print(kappa,"delayed: %.4f/walk (a=%.2f b=%.2f) walks to 1e-3 %d | heavy ball two walks/iter: %.4f/iter, walks %d"%(d[0],d[1],d[2],math.log(1e-3)/math.log(d[0]),h[0],2*math.log(1e-3)/math.log(h[0])))
