#!/usr/bin/env python3
# What the iteration caps of engine/sim/solvers/dfsph.cpp (next_iteration_cap(), the planning record two
# frames back, the most over the last 16 records) issue beyond what the steps ran, replayed from a run's
# records (profile --records): empty iterations a step, and for other windows and factors the frames whose
# steps needed more than the cap they would have had (a first-order count: the trajectory would differ).
#     python3 caps.py 1m/*.csv
import csv, math, sys, glob
def sim(f, window, factor, add, stop_rule):
    r=list(csv.DictReader(open(f)))
    least,most=2,100
    recent=[]; cap=most
    waste=0; steps=0; ran=0; stopframes=0; truestops=0
    for n,row in enumerate(r):
        if n>=2:
            p=r[n-2]
            recent.append(int(p['most_iterations'])); recent=recent[-window:]
            need=max(recent)
            if int(p['unconverged'])>0: cap = most if stop_rule=='most' else min(most, max(cap*2, math.ceil(factor*need)+add))
            else: cap=min(max(math.ceil(factor*need)+add,least),most)
        s=int(row['substeps']); it=int(row['iterations']); m=int(row['most_iterations'])
        if m>cap: stopframes+=1
        if int(row['unconverged'])>0: truestops+=1
        waste+=max(cap*s-it,0); steps+=s; ran+=it
    return waste/steps, stopframes, truestops
for f in sys.argv[1:]:
    print(f)
    for args in [(16,1.5,2,'most'),(8,1.5,2,'most'),(4,1.5,2,'most'),(16,1.25,2,'most'),(8,1.25,2,'most'),(4,1.25,2,'most'),(4,1.25,2,'double'),(8,1.0,4,'double'),(4,1.0,4,'double')]:
        w,sf,ts=sim(f,*args)
        print('  window %2d x%.2f +%d stop:%-6s empty/step %5.1f  frames needing more than the cap %3d (frames with stops in the run %d)'%(args+(w,sf,ts)))
