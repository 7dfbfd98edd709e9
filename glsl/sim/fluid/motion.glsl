// The end of a step, shared by every solver's integration (docs/SPH.md (6), (8)): the last-resort
// projection out of the tank's walls and the obstacles, and the guard's records. Needs fluid.glsl and
// the pass's local size before it, and declares the Obstacles block.
//
// The projection: a particle whose centre the step put more than kSlack spacings inside a solid (the
// tank's walls and floor, and the obstacles) goes back to that depth, and the part of its velocity
// into the solid is removed. The particle boundary keeps resting fluid half a spacing off every
// surface, and under load lets it dip to 0.15 dx past it (the floor under a column in its start-up
// ringing); the slack leaves that alone, so the projection catches only what the particle boundary
// lets through (splash particles too sparse for any pressure, thin obstacles).

// engine/sim/boundary.h obstacle_shapes(): (count, 0, 0, 0), then per obstacle a box as (min, 0),
// (max, 0) or a sphere as (center, 1), (radius, 0, 0, 0); the paddle as (center, 2), (radius, velocity).
layout(std430) readonly buffer Obstacles { vec4 obstacle[]; };

#include "extremes.glsl"

const float kSlack = 0.25;   // spacings a centre may lie inside a solid before it is projected

// The tank's walls and floor, and its lid when the tank is closed (domain_max.w = 1). The guard's
// domain is the tank grown by one spacing at the walls and floor, and at a lid (engine/sim/fluid.cpp,
// sph_params), so the tank is the domain less that spacing. A wall is a slab as thick as its boundary
// layers, ceil(h/dx) + 1 spacings (engine/sim/boundary.cpp); the side walls bound the fluid at every
// height (the guard's domain does), so a splash thrown above an open top comes back down into the
// tank. Whether a particle is inside is decided by where its step began, x0, not by where it ended: a
// step that began on the fluid's side of a slab's far face ends at the wall however far it went (PBF's
// fixed step carries a splash particle further than a slab is thick, docs/PBF.md (P1)); a particle
// whose step began beyond a far face went through a wall earlier: it is left where it is, for the guard
// to report.
void keep_in_tank(vec3 x0, inout vec3 x, inout vec3 v) {
    float slack = kSlack * sph.spacing;
    vec3 lo = sph.domain_min.xyz + sph.spacing - slack;
    vec3 hi = sph.domain_max.xyz - sph.spacing + slack;
    bool lid = sph.domain_max.w > 0.5;
    float thick = (ceil(sph.h / sph.spacing) + 1.0) * sph.spacing - slack;
    for (int a = 0; a < 3; ++a) {
        if (x[a] < lo[a] && x0[a] > lo[a] - thick) { x[a] = lo[a]; v[a] = max(v[a], 0.0); }
        if ((a != 1 || lid) && x[a] > hi[a] && x0[a] < hi[a] + thick) { x[a] = hi[a]; v[a] = min(v[a], 0.0); }
    }
}

// Obstacles are solid throughout: a centre more than the slack inside one goes back to that depth
// (a sphere: radially; a box: through the face it entered by, which is the face of least depth among
// those the particle was outside of before the step, so it cannot tunnel through a thin box). The
// slack is at most a quarter of a box's thickness or half a sphere's radius. A step from x0 outside
// that crosses the solid and leaves it again (a fast particle, or PBF's fixed step, docs/PBF.md (P1))
// stops where the segment x0 -> x first meets it (enter_sphere, enter_box), as one inside would.
//
// The paddle (engine/sim/boundary.h) is a kinematic sphere that moves with velocity u: a moving wall
// (docs/SPH.md (9)). It has no slack: a centre inside it goes out radially onto its surface,
//     x <- c + R n,   n = (x - c) / |x - c|,
// and leaves with at least the paddle's normal velocity,
//     v <- v + max(u.n - v.n, 0) n,
// so that fluid it runs into moves ahead of it, never through it. R = 0 (parked): nothing to do.
void keep_out_of_paddle(vec3 x0, vec4 a, vec4 b, inout vec3 x, inout vec3 v) {
    vec3 d = x - a.xyz;
    float r = length(d);
    if (r >= b.x) return;
    vec3 away = x0 - a.xyz;
    vec3 normal = r > 1e-6 * b.x ? d / r : (length(away) > 0.0 ? normalize(away) : vec3(0.0, 1.0, 0.0));
    x = a.xyz + b.x * normal;
    v += max(dot(b.yzw, normal) - dot(v, normal), 0.0) * normal;
}

// The fraction t in [0, 1] of the segment x0 -> x at which it first meets the sphere (c, r) from
// outside; 2 when it does not, or when x0 is inside (the static test's case).
float enter_sphere(vec3 x0, vec3 x, vec3 c, float r) {
    vec3 d = x - x0, m = x0 - c;
    float a = dot(d, d), b = dot(m, d), e = dot(m, m) - r * r;
    if (e <= 0.0 || a == 0.0 || b >= 0.0) return 2.0;   // inside, at rest, or moving away
    float disc = b * b - a * e;
    if (disc < 0.0) return 2.0;
    float t = (-b - sqrt(disc)) / a;
    return t <= 1.0 ? t : 2.0;
}

// The same for the box [lo, hi] (the slab method): t and the axis of the face entered, or t = 2.
vec2 enter_box(vec3 x0, vec3 x, vec3 lo, vec3 hi) {
    if (all(greaterThan(x0, lo)) && all(lessThan(x0, hi))) return vec2(2.0, 0.0);
    vec3 d = x - x0;
    float t0 = 0.0, t1 = 1.0;
    int axis = -1;
    for (int c = 0; c < 3; ++c) {
        if (d[c] == 0.0) {
            if (x0[c] <= lo[c] || x0[c] >= hi[c]) return vec2(2.0, 0.0);
            continue;
        }
        float ta = (lo[c] - x0[c]) / d[c], tb = (hi[c] - x0[c]) / d[c];
        float near = min(ta, tb), far = max(ta, tb);
        if (near > t0) { t0 = near; axis = c; }
        t1 = min(t1, far);
    }
    return axis >= 0 && t0 < t1 ? vec2(t0, float(axis)) : vec2(2.0, 0.0);
}

void keep_out_of_obstacles(vec3 x0, inout vec3 x, inout vec3 v) {
    uint n = uint(obstacle[0].x);
    float slack = kSlack * sph.spacing;
    for (uint k = 0u; k < n; ++k) {
        vec4 a = obstacle[1u + 2u * k], b = obstacle[2u + 2u * k];
        if (a.w > 1.5) {
            keep_out_of_paddle(x0, a, b, x, v);
        } else if (a.w > 0.5) {   // sphere: centre a.xyz, radius b.x
            float inner = b.x - min(slack, 0.5 * b.x);
            float t = enter_sphere(x0, x, a.xyz, inner);
            if (t <= 1.0) {
                x = x0 + t * (x - x0);
                vec3 n = normalize(x - a.xyz);
                v -= min(dot(v, n), 0.0) * n;
                continue;
            }
            vec3 d = x - a.xyz;
            float r = length(d);
            if (r >= inner) continue;
            vec3 normal = r > 1e-6 * b.x ? d / r : (length(x0 - a.xyz) > 0.0 ? normalize(x0 - a.xyz) : vec3(0.0, 1.0, 0.0));
            x = a.xyz + inner * normal;
            v -= min(dot(v, normal), 0.0) * normal;
        } else {           // box [a, b], its solid for this purpose [lo, hi]
            vec3 inset = min(vec3(slack), 0.25 * (b.xyz - a.xyz));
            vec3 lo = a.xyz + inset, hi = b.xyz - inset;
            vec2 hit = enter_box(x0, x, lo, hi);
            if (hit.x <= 1.0) {
                int c = int(hit.y);
                bool low = x0[c] <= lo[c];
                x = x0 + hit.x * (x - x0);
                x[c] = low ? lo[c] : hi[c];
                v[c] = low ? min(v[c], 0.0) : max(v[c], 0.0);
                continue;
            }
            if (any(lessThanEqual(x, lo)) || any(greaterThanEqual(x, hi))) continue;
            vec3 below = x - lo, above = hi - x;   // depths past the lower and upper faces
            bool entered = any(lessThanEqual(x0, lo)) || any(greaterThanEqual(x0, hi));
            float best = 3.4e38;
            int axis = 0;
            float side = -1.0;
            for (int c = 0; c < 3; ++c) {
                if ((!entered || x0[c] <= lo[c]) && below[c] < best) { best = below[c]; axis = c; side = -1.0; }
                if ((!entered || x0[c] >= hi[c]) && above[c] < best) { best = above[c]; axis = c; side = 1.0; }
            }
            x[axis] = side < 0.0 ? lo[axis] : hi[axis];
            v[axis] = side < 0.0 ? min(v[axis], 0.0) : max(v[axis], 0.0);
        }
    }
}

vec3 recorded_x_;        // the invocation's particle's end-of-step position, for record_maxima()
shared vec3 wg_fastest_x_;

// Guard records (StepState) for the particle that ends the step at x with velocity v: non-finite
// values and particles outside the domain (an atomic each: rare); returns the bits of |v| and of the
// surge front (x - domain_min.x for particles within sph.front_band of domain_min.y), for the
// caller's workgroup maxima (record_maxima).
uvec2 record_particle(uint i, vec3 x, vec3 v) {
    recorded_x_ = x;
    if (any(isnan(x)) || any(isinf(x)) || any(isnan(v)) || any(isinf(v))) {
        atomicAdd(step.nan_count, 1u);
        atomicMin(step.nan_index, i);
        return uvec2(0u);
    }
    if (any(lessThan(x, sph.domain_min.xyz)) || any(greaterThan(x, sph.domain_max.xyz))) {
        atomicAdd(step.escaped_count, 1u);
        atomicMin(step.escaped_index, i);
    }
    uint front = x.y - sph.domain_min.y < sph.front_band ? max_bits(x.x - sph.domain_min.x) : 0u;
    return uvec2(max_bits(length(v)), front);
}

// The workgroup's largest speed and front: into StepState by one atomic a workgroup each (the step's
// max_speed, the time step's input, and the front), and the fastest particle with its position into the
// workgroup's FrameExtreme entry (extremes.glsl). Every invocation calls it (barriers); `bits` is
// record_particle()'s result, or 0 for invocations past the count. The fastest particle's position goes
// with its index (the second workgroup_max's barriers order the winner's shared write before
// invocation 0 reads it).
void record_maxima(uvec2 bits, uint i) {
    uvec2 s = workgroup_max(bits.x, i);
    if (s.x != 0u && i == s.y) wg_fastest_x_ = recorded_x_;
    uvec2 f = workgroup_max(bits.y, i);
    if (gl_LocalInvocationIndex == 0u) {
        atomicMax(step.max_speed, s.x);
        if (s.x != 0u) keep_extreme(RANRYU_EXTREME_SPEED, s, wg_fastest_x_);
        atomicMax(step.front, f.x);
    }
}
