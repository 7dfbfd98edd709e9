#!/usr/bin/env python3
# loops.py PREFIX: for each PREFIX-K.txt that ../2026-12-01-h200-kernel-constants/sass.py wrote (one program's
# disassembly), its highest register, its instructions that read or write the per-thread stack in shared
# memory ([R1...]) and each loop of at most 300 instructions (a backward branch): its address range,
# instructions, global loads (g) and stack reads and writes (s).
import re,sys,glob
for f in sorted([p for p in glob.glob(sys.argv[1]+'-*.txt') if re.search(r'-(\d+)\.txt$',p)], key=lambda p:int(re.search(r'-(\d+)\.txt$',p).group(1))):
    L=open(f).read().splitlines()
    if not L: continue
    k=re.search(r'-(\d+)\.txt$',f).group(1)
    regs=max([int(x) for x in re.findall(r'\bR(\d+)\b','\n'.join(L))]+[0])
    stk=sum(bool(re.search(r'\b(LDS|STS)\b.*\[R1\b',x)) for x in L)
    out=[]
    for n,l in enumerate(L):
        m=re.search(r'/\*([0-9a-f]{4,5})\*/.*\bBRA (0x[0-9a-f]+)',l)
        if m:
            a=int(m.group(1),16); t=int(m.group(2),16)
            if t<a:
                body=[x for x in L if (mm:=re.search(r'/\*([0-9a-f]{4,5})\*/',x)) and t<=int(mm.group(1),16)<=a]
                if len(body)>300: continue
                ldg=sum('LDG' in x for x in body); s=sum(bool(re.search(r'\b(LDS|STS)\b.*\[R1\b',x)) for x in body)
                out.append(f'{hex(t)}-{hex(a)}:{len(body)}i/{ldg}g/{s}s')
    print(k,'R',regs,'stack',stk,' '.join(out))
