# WCSPH dam break at 1M with Monaghan's artificial viscosity (approaching pairs), alpha from ALPHAS, via --shader-dir copies.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
o=$out/av; mkdir -p $o
f=$o/db.json; dx=$(python3 scripts/gpu/scene-at.py dam-break $f ${PARTICLES:-1000000})
for a in ${ALPHAS}; do
  d=/tmp/g-av$a; rm -rf $d; cp -r glsl $d
  python3 - $d/sim/wcsph/compute_forces.comp $a <<'PY'
import sys
p,a=sys.argv[1],sys.argv[2]; s=open(p).read()
s=s.replace("vec3 vi_, di_, a_pressure_, a_viscous_, a_wall_;","vec3 vi_, di_, a_pressure_, a_viscous_, a_wall_, a_art_;")
s=s.replace("    a_viscous_ += (2.0 * dot(vi_ - velocity[j].xyz, d) / ((r2 + 0.01 * sph.h * sph.h) * (di_.x + tj.x))) * g;",
"    float vx = dot(vi_ - velocity[j].xyz, d);\n    vec3 t = (2.0 * vx / ((r2 + 0.01 * sph.h * sph.h) * (di_.x + tj.x))) * g;\n    a_viscous_ += t;\n    if (vx < 0.0) a_art_ += t;")
s=s.replace("a_pressure_ = a_viscous_ = a_wall_ = vec3(0.0);","a_pressure_ = a_viscous_ = a_wall_ = a_art_ = vec3(0.0);")
s=s.replace("+ 10.0 * sph.viscosity * a_viscous_)","+ 10.0 * sph.viscosity * a_viscous_ + %s * sph.sound_speed * sph.h * a_art_)" % a)
assert s.count("a_art_")==4, s.count("a_art_")
open(p,'w').write(s)
PY
  timeout --preserve-status ${RUN_TIMEOUT:-100} $B profile --shader-dir $d --scene $f --solver wcsph --spacing $dx --shading particles --size 640x360 \
    --frames ${FRAMES:-72} --warmup 0 --records $o/a$a.csv > $o/a$a.txt 2>&1
  echo "alpha $a rc $?: $(grep -m1 'unstable' $o/a$a.txt) $(grep -m1 'fps and real' $o/a$a.txt)"
  python3 -c "
import csv; r=list(csv.DictReader(open('$o/a$a.csv')))
print(' frames',len(r),'maxrho',max(float(x['max_density']) for x in r),'maxv',max(float(x['max_speed']) for x in r),'substeps',sum(float(x['substeps']) for x in r)/len(r))
print(' ', [(x['frame'],round(float(x['max_speed']),1),round(float(x['max_density']),3)) for x in r[55::2]])"
done
