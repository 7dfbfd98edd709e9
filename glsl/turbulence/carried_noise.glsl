// The noise carried with the fluid (docs/METHOD.md §4, temporal coherence; engine/turbulence/noise.h has
// the CPU reference). Each particle keeps, per phase p = 0, 1, the position s_p where it was when the
// phase's current epoch began, and samples the octave sum there:
//
//     u_p = t/T + p/2,   k_p = floor(u_p),   w_p = sin²(π u_p)            (w_0 + w_1 = 1)
//     q_p = s_p + o(2 k_p + p) + d                                         (d: an offset, m)
//     y_c = (w_0 y(q_0) + w_1 y(q_1)) / √(w_0² + w_1²)
//
// While an epoch lasts q_p is fixed: the particle carries the value of the noise it was seeded with
// wherever the flow takes it (the field is advected with the fluid, not sampled where the particle
// is now). Every T each phase is re-seeded, s_p = x, with a new epoch offset o (a fresh piece of the
// noise), at the moment its weight is 0; the other phase then carries the whole field. So y_c is
// continuous in time (C¹: w_p is), a particle's noise drifts smoothly over a time T, and a long
// stretching flow never distorts a phase for more than T. The 1/√(w_0² + w_1²) keeps the variance of
// two independent fields' blend equal to one field's (it dips to ½ at w_0 = w_1 otherwise).
// The includer includes shared/bindings.h and curl_noise.glsl first.
#ifndef RANRYU_CARRIED_NOISE_GLSL
#define RANRYU_CARRIED_NOISE_GLSL

// o(m) (m): a per-epoch offset within one period of the coarsest octave's tile, n·2^−lmin m.
// Keep in step with epoch_offset() in engine/turbulence/noise.cpp.
vec3 epoch_offset(float m, int n, int lmin) {
    return fract(m * vec3(0.7548777, 0.5698403, 0.6180340) + vec3(0.1, 0.3, 0.7)) * (float(n) * exp2(-float(lmin)));
}

// The epoch of phase p at time t: floor(t/T + p/2).
float noise_epoch(int p, float t, float period) { return floor(t / period + 0.5 * float(p)); }

// Re-seeds the phases whose epoch has changed since they were seeded: s_p = x, and the phase's value
// y(q_p) for the octaves lmin..lmax, which stays fixed until the next re-seeding (q_p does).
NoiseSeed reseed_noise(NoiseSeed s, vec3 x, float t, float period, int lmin, int lmax, float beta, int n) {
    for (int p = 0; p < 2; ++p) {
        float k = noise_epoch(p, t, period);
        if (s.phase[p].w != k) {
            s.phase[p] = vec4(x, k);
            s.value[p] = vec4(curl_noise_octaves(x + epoch_offset(2.0 * k + float(p), n, lmin), lmin, lmax, beta, n), 0.0);
        }
    }
    return s;
}

// The weights w_p of the two phases at t, and 1/√(w_0² + w_1²).
vec3 carried_weights(float t, float period) {
    vec2 w = sin(3.14159265 * fract(vec2(t / period) + vec2(0.0, 0.5)));   // fract: sin's argument stays in [0, π]
    w *= w;
    return vec3(w, inversesqrt(dot(w, w)));
}

// y_c at offset 0 from the seeded positions, from the values the re-seeding stored: the blend alone,
// with no noise to evaluate (the value of carried_noise(s, vec3(0), ...) once s is re-seeded at t).
vec3 carried_value(NoiseSeed s, float t, float period) {
    vec3 w = carried_weights(t, period);
    return (w.x * s.value[0].xyz + w.y * s.value[1].xyz) * w.z;
}

// y_c at time t for the seeds s, sampled at offset d (m) from the seeded positions, octaves lmin..lmax.
vec3 carried_noise(NoiseSeed s, vec3 d, float t, float period, int lmin, int lmax, float beta, int n) {
    vec3 w = carried_weights(t, period);
    vec3 y = vec3(0.0);
    for (int p = 0; p < 2; ++p) {
        if (w[p] > 0.0) {
            // The seeded epoch (= k_p once the force pass has re-seeded at t) names the offset.
            vec3 q = s.phase[p].xyz + epoch_offset(2.0 * s.phase[p].w + float(p), n, lmin) + d;
            y += w[p] * curl_noise_octaves(q, lmin, lmax, beta, n);
        }
    }
    return y * w.z;
}

#endif
