// Curl of wavelet noise (docs/METHOD.md §4; engine/turbulence/noise.h has the construction and units).
// N = (N1, N2, N3): three tiles of Cook & DeRose wavelet noise, each a quadratic B-spline with the
// tile's values as coefficients (C¹). w = ∇×N is the analytic curl of that spline: the gradients come
// from the derivatives of the B-spline weights, so w is exactly divergence-free as a function.
// The includer includes shared/bindings.h first; this file declares the tiles buffer.
#ifndef RANRYU_CURL_NOISE_GLSL
#define RANRYU_CURL_NOISE_GLSL

layout(std430) readonly buffer NoiseTiles { float noise_tiles[]; };

// i mod n in [0, n) for any i (GLSL's % is undefined for negative operands).
int noise_wrap(int i, int n) {
    return i >= 0 ? i % n : n - 1 - ((-i - 1) % n);
}

// Per-octave offset (noise units), so the octaves that share the tiles are not aligned.
// Keep in step with octave_offset() in engine/turbulence/noise.cpp.
vec3 octave_offset(int i) {
    float fi = float(i);
    return fract(fi * vec3(0.6180340, 0.7548777, 0.5698403)) * 17.0;
}

// w(q) = ∇_q × N(q), q in tile cells; tiles of n³ values, tile c at offset c·n³.
vec3 curl_noise(vec3 q, int n) {
    // Cook & DeRose's evaluation: mid = ceil(q − ½), t = mid − (q − ½); weights of cells mid−1, mid,
    // mid+1 are t²/2, 1 − t²/2 − (1−t)²/2, (1−t)²/2; their q-derivatives −t, 2t − 1, 1 − t.
    vec3 midf = ceil(q - 0.5);
    vec3 t = midf - (q - 0.5);
    vec3 w0 = 0.5 * t * t, w2 = 0.5 * (1.0 - t) * (1.0 - t), w1 = 1.0 - w0 - w2;
    vec3 d0 = -t, d1 = 2.0 * t - 1.0, d2 = 1.0 - t;
    mat3 W = mat3(w0, w1, w2);   // W[f][axis]
    mat3 D = mat3(d0, d1, d2);
    ivec3 mid = ivec3(midf);
    int n3 = n * n * n;
    vec3 g1 = vec3(0.0), g2 = vec3(0.0), g3 = vec3(0.0);   // ∇N1, ∇N2, ∇N3
    for (int fz = 0; fz < 3; ++fz) {
        int cz = noise_wrap(mid.z + fz - 1, n);
        for (int fy = 0; fy < 3; ++fy) {
            int cy = noise_wrap(mid.y + fy - 1, n);
            float wyz = W[fy].y * W[fz].z, dyz = D[fy].y * W[fz].z, ydz = W[fy].y * D[fz].z;
            for (int fx = 0; fx < 3; ++fx) {
                int c = noise_wrap(mid.x + fx - 1, n) + n * (cy + n * cz);
                vec3 g = vec3(D[fx].x * wyz, W[fx].x * dyz, W[fx].x * ydz);
                g1 += noise_tiles[c] * g;
                g2 += noise_tiles[c + n3] * g;
                g3 += noise_tiles[c + 2 * n3] * g;
            }
        }
    }
    return vec3(g3.y - g2.z, g1.z - g3.x, g2.x - g1.y);
}

// y(x) = Σ_{i=lmin}^{lmax} w(2^i x + o_i) · 2^(−β(i − lmin)), x in metres (a tile cell of octave 0 is 1 m).
vec3 curl_noise_octaves(vec3 x, int lmin, int lmax, float beta, int n) {
    vec3 y = vec3(0.0);
    for (int i = lmin; i <= lmax; ++i)
        y += curl_noise(exp2(float(i)) * x + octave_offset(i), n) * exp2(-beta * float(i - lmin));
    return y;
}

#endif
