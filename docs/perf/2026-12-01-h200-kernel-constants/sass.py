#!/usr/bin/env python3
# sass.py CACHEDIR PREFIX: the machine code of each program in an NVIDIA GL shader cache (README.md here),
# disassembled to PREFIX-K.txt (K: the program's place in the cache file) with nvdisasm ($NVDISASM, else
# Triton's under /tmp/tt); prints each program's group size, shared memory, storage blocks, instructions
# and highest register.
import glob, os, re, struct, subprocess, sys
N = os.environ.get('NVDISASM', '/tmp/tt/triton/backends/nvidia/bin/nvdisasm')
cdir,prefix=sys.argv[1],sys.argv[2]
f=[p for p in glob.glob(cdir+'/**/*.bin',recursive=True)][0]
b=open(f,'rb').read()
idx=[m.start() for m in re.finditer(rb'!!NVcp5.0',b)]
for k,i in enumerate(idx):
    e=b.find(b'\nEND\n',i)+5
    t=b[i:e].decode('latin1')
    nxt=idx[k+1] if k+1<len(idx) else len(b)
    g=b[e:nxt]; z=g.find(b'\x28\xb5\x2f\xfd')
    d=subprocess.run(['zstd','-d','-c'],input=g[z:],capture_output=True).stdout
    size=struct.unpack_from('<I',d,0x44)[0]
    off=next((o for o in range(0x100,0x400,16) if d[o]==0x19 and d[o+1]==0x79),None)
    if off is None: continue
    open(f'{prefix}-{k}.sass','wb').write(d[off:off+size])
    out=subprocess.run([N,'-b','SM90',f'{prefix}-{k}.sass'],capture_output=True,text=True).stdout
    open(f'{prefix}-{k}.txt','w').write(out)
    regs=max([int(x) for x in re.findall(r'\bR(\d+)\b',out)]+[0])
    gs=re.search(r'GROUP_SIZE ([0-9 ]+);',t); sm=re.search(r'SHARED_MEMORY (\d+)',t)
    nst=len(re.findall(r'^STORAGE',t,re.M))
    print(k,'group',gs.group(1) if gs else '-','shared',sm.group(1) if sm else '-','storage',nst,'instr',out.count('/*')-0,'maxreg',regs)
