#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: what a neighbour walk's time is made of
# (docs/PERFORMANCE.md "The neighbour walk's per-pair cost"). Each variant is a copy of glsl/ with one
# change, run with --shader-dir on the dam break at 1M particles (spacing 0.002, frames 20-30: the
# surge), PBF (its lambda and correction walks) and, for the variants named in DFSPH_VARIANTS, DFSPH.
#     current     glsl/ as committed
#     old-kernel  kernel_w and kernel_grad as before 2026-11-25 night: branches on q, divisions by h
#     math2       the lambda and correction passes evaluate every pair's kernel twice (results kept)
#     flat        the masked walk runs one loop over all nine runs' bits (fewer idle lanes)
#     prefetch    the masked walk loads all nine runs' starts and masks before it visits any
#     int-power   s_corr's (W/W(dq))^n by repeated squaring instead of pow()
#     ls64, ls256 the lambda and correction passes at 64 and 256 invocations a workgroup
# Prints each pass's ms a call; reports under $OUT.
#     VARIANTS="current old-kernel" DFSPH_VARIANTS="current old-kernel" scripts/gpu/walk-variants.sh
. "$(dirname "$0")/env.sh" walk-variants-out
variants=${VARIANTS:-current old-kernel math2 flat prefetch int-power ls64 ls256 current}
dfsph_variants=${DFSPH_VARIANTS:-current old-kernel}
work=$(mktemp -d)
for v in $(echo $variants $dfsph_variants | tr ' ' '\n' | sort -u); do
  cp -r glsl "$work/$v"
  python3 - "$work/$v" "$v" <<'PY' || exit 2
import sys
root, v = sys.argv[1], sys.argv[2]
def patch(path, old, new):
    p = f"{root}/{path}"; s = open(p).read()
    assert old in s, f"{v}: {path} has changed; update scripts/gpu/walk-variants.sh"
    open(p, "w").write(s.replace(old, new))
if v == "old-kernel":
    patch("sim/kernel.glsl", """    float inv_h = 1.0 / h;
    float q = r * inv_h;
    float t = max(1.0 - q, 0.0);
    float shape = q <= 0.5 ? 6.0 * q * q * (q - 1.0) + 1.0 : 2.0 * t * t * t;
    return (8.0 / kPi) * inv_h * inv_h * inv_h * shape;""", """    float q = r / h;
    float k = 8.0 / (kPi * h * h * h);
    if (q <= 0.5) return k * (6.0 * q * q * (q - 1.0) + 1.0);
    if (q <= 1.0) { float t = 1.0 - q; return k * 2.0 * t * t * t; }
    return 0.0;""")
    patch("sim/kernel.glsl", """    float inv_h = 1.0 / h;
    float q = r * inv_h;
    float t = max(1.0 - q, 0.0);
    float f = q <= 0.5 ? q * (3.0 * q - 2.0) : -t * t;
    float l = (48.0 / kPi) * inv_h * inv_h * inv_h * inv_h;
    return r > 1e-9 * h ? (l * f / r) * d : vec3(0.0);""", """    float q = r / h;
    if (r <= 1e-9 * h || q > 1.0) return vec3(0.0);
    float l = 48.0 / (kPi * h * h * h);
    float f = q <= 0.5 ? q * (3.0 * q - 2.0) : -(1.0 - q) * (1.0 - q);
    return (l * f / (r * h)) * d;""")
elif v == "math2":
    patch("sim/pbf/compute_lambda.comp", """    float r = sqrt(r2);
    sum_w_ += sph.mass * kernel_w(r, sph.h);
    vec3 g = sph.mass * kernel_grad(d, r, sph.h);""", """    float r = sqrt(r2), rb = sqrt(r2 * 1.0000002);
    sum_w_ += sph.mass * 0.5 * (kernel_w(r, sph.h) + kernel_w(rb, sph.h));
    vec3 g = sph.mass * 0.5 * (kernel_grad(d, r, sph.h) + kernel_grad(d * 1.0000001, rb, sph.h));""")
    patch("sim/pbf/correct_positions.comp", """    float r = sqrt(r2);
    float s_corr = -pbf.s_corr_scale * pow(kernel_w(r, sph.h) * pbf.inv_w_dq, pbf.s_corr_n);
    fluid_ += (lambda_i_ + lambda[j] + s_corr) * kernel_grad(d, r, sph.h);""", """    float r = sqrt(r2), rb = sqrt(r2 * 1.0000002);
    float s_corr = -pbf.s_corr_scale * 0.5 * (pow(kernel_w(r, sph.h) * pbf.inv_w_dq, pbf.s_corr_n) + pow(kernel_w(rb, sph.h) * pbf.inv_w_dq, pbf.s_corr_n));
    fluid_ += (lambda_i_ + lambda[j] + s_corr) * 0.5 * (kernel_grad(d, r, sph.h) + kernel_grad(d * 1.0000001, rb, sph.h));""")
elif v in ("flat", "prefetch"):
    walls = """        if (!walls) return;
        FOR_EACH_RUN {
            uvec2 run = NEIGHBOUR_RUN(c, false);
            for (uint b = run.x; b < run.y; ++b) {
                vec3 d = xi - boundary[b].xyz;
                float r2 = dot(d, d);
                if (r2 >= h2) continue;
                visit_boundary(b, d, r2);
            }
        }
        return;
    }
#endif
"""
    visit = """                vec3 d = xi - position[j].xyz;
                visit_fluid(j, d, dot(d, d));
"""
    body = ("""        uint r = 0u, start = neighbours[i], mask = neighbours[sph.particle_count + i];
        for (;;) {
            while (mask == 0u && ++r < 9u) {
                start = neighbours[2u * r * sph.particle_count + i];
                mask = neighbours[(2u * r + 1u) * sph.particle_count + i];
            }
            if (mask == 0u) break;
            uint j = start + uint(findLSB(mask));
            mask &= mask - 1u;
""" + visit + "        }\n") if v == "flat" else ("""        uint st[9], mk[9];
        for (uint r = 0u; r < 9u; ++r) {
            st[r] = neighbours[2u * r * sph.particle_count + i];
            mk[r] = neighbours[(2u * r + 1u) * sph.particle_count + i];
        }
        for (uint r = 0u; r < 9u; ++r) {
            uint start = st[r], mask = mk[r];
            while (mask != 0u) {
                uint j = start + uint(findLSB(mask));
                mask &= mask - 1u;
""" + visit + "            }\n        }\n")
    patch("sim/fluid/neighbours.glsl", "    uint run_index = 0u;\n    FOR_EACH_RUN {",
          "    uint run_index = 0u;\n#if defined(RANRYU_NEIGHBOUR_MASKS) && defined(RANRYU_MERGE_ROWS)\n    if (masked) {\n"
          + body + walls + "    FOR_EACH_RUN {")
elif v == "int-power":
    patch("sim/pbf/correct_positions.comp", "pow(kernel_w(r, sph.h) * pbf.inv_w_dq, pbf.s_corr_n)",
          "int_power(kernel_w(r, sph.h) * pbf.inv_w_dq, uint(pbf.s_corr_n))")
    patch("sim/pbf/correct_positions.comp", "float lambda_i_;", """float int_power(float x, uint n) {
    float p = 1.0;
    for (; n != 0u; n >>= 1u, x *= x) if ((n & 1u) != 0u) p *= x;
    return p;
}
float lambda_i_;""")
elif v in ("ls64", "ls256"):
    for f in ("compute_lambda.comp", "correct_positions.comp"):
        patch(f"sim/pbf/{f}", "layout(local_size_x = 128) in;", f"layout(local_size_x = {v[2:]}) in;")
PY
done
prof() {  # solver, variant
  local name="$1-$2-$((++run))"
  $B profile --scene dam-break --solver "$1" --spacing 0.002 --frames "$3" --warmup 20 --size 640x360 \
    --shading particles --shader-dir "$work/$2" --json "$out/$name.json" > "$out/$name.txt" 2>&1
  echo "== $1 $2 (rc $?): ms a call"
  grep -E "^(pbf\.|dfsph\.|frame \(GPU)" "$out/$name.txt" | awk '{print "  " $1, $(NF-1)}'
}
run=0
for v in $variants; do prof pbf "$v" 10; done
for v in $dfsph_variants; do prof dfsph "$v" 5; done
rm -rf "$work"
