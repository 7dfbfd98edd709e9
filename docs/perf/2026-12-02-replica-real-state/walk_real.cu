// A CUDA replica of ranryu's masked neighbour walk (glsl/sim/fluid/neighbours.glsl, the DFSPH
// accelerate pass glsl/sim/dfsph/accelerate.comp), to find the walk's floor with hardware counters
// (ncu), which OpenGL's shaders do not give. Same data layout as the engine: particles sorted by linear
// cell key (x fastest), cell = h = 2 dx, the 9 merged x-rows, masks stored [2r*N + i] = start and
// [(2r+1)*N + i] = bits j - start.
//     nvcc -O3 -arch=sm_90 -Xptxas -v walk_real.cu -o walk_real && ./walk_real [nx ny nz [block]]
// 2026-12-02: also ./walk_real --ply FILE DX [block]: the positions of a ranryu particle export (binary PLY,
// `ranryu record --export-particles ply`: x y z first, 4-byte fields) at spacing DX, in the dam break's
// tank (1.0 x 0.5 x 0.1), instead of the jittered lattice; kappa from the file's pressure field where it has
// one (any smooth field does for timing). Walls are not walked, as before.
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <vector>
#include <string>
#include <cstring>
#include <fstream>
#include <thrust/device_ptr.h>
#include <thrust/sort.h>
#include <thrust/sequence.h>
#include <thrust/gather.h>

#define CK(x) do { cudaError_t e = (x); if (e != cudaSuccess) { printf("%s: %s\n", #x, cudaGetErrorString(e)); exit(1); } } while (0)

struct Grid { float3 origin; float cell; int3 dims; };

__device__ int3 cell_of(const Grid& g, float3 x) {
    int3 c = make_int3(floorf((x.x - g.origin.x) / g.cell), floorf((x.y - g.origin.y) / g.cell), floorf((x.z - g.origin.z) / g.cell));
    c.x = min(max(c.x, 0), g.dims.x - 1); c.y = min(max(c.y, 0), g.dims.y - 1); c.z = min(max(c.z, 0), g.dims.z - 1);
    return c;
}
__device__ uint32_t key_of(const Grid& g, int3 c) { return c.x + g.dims.x * (c.y + g.dims.y * c.z); }

__global__ void keys(const float4* x, uint32_t* k, int n, Grid g) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) k[i] = key_of(g, cell_of(g, make_float3(x[i].x, x[i].y, x[i].z)));
}
__global__ void ranges(const uint32_t* k, uint2* r, int n) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    if (i == 0 || k[i] != k[i - 1]) r[k[i]].x = i;
    if (i == n - 1 || k[i] != k[i + 1]) r[k[i]].y = i + 1;
}

__device__ uint2 row_run(const uint2* r, const Grid& g, int3 c, int dy, int dz) {
    int y = c.y + dy, z = c.z + dz;
    if (y < 0 || z < 0 || y >= g.dims.y || z >= g.dims.z) return make_uint2(0, 0);
    uint32_t first = 0xFFFFFFFFu, last = 0;
    for (int dx = -1; dx <= 1; ++dx) {
        int x = c.x + dx;
        if (x < 0 || x >= g.dims.x) continue;
        uint2 q = r[key_of(g, make_int3(x, y, z))];
        if (q.y > q.x) { first = min(first, q.x); last = max(last, q.y); }
    }
    return first == 0xFFFFFFFFu ? make_uint2(0, 0) : make_uint2(first, last);
}

// The density pass's part that matters here: the masks (and a count of pairs, and the candidates).
__global__ void masks(const float4* x, const uint2* r, uint32_t* m, uint32_t* complete, unsigned long long* counts, int n, Grid g, float h) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float3 xi = make_float3(x[i].x, x[i].y, x[i].z);
    int3 c = cell_of(g, xi);
    uint32_t ok = 1, pairs = 0, cand = 0;
    int rr = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy, ++rr) {
            uint2 run = row_run(r, g, c, dy, dz);
            uint32_t bits = 0;
            for (uint32_t j = run.x; j < run.y; ++j) {
                ++cand;
                float dx0 = xi.x - x[j].x, dy0 = xi.y - x[j].y, dz0 = xi.z - x[j].z;
                if (dx0 * dx0 + dy0 * dy0 + dz0 * dz0 >= h * h || j == (uint32_t)i) continue;
                if (j - run.x >= 32) { ok = 0; continue; }
                bits |= 1u << (j - run.x);
                ++pairs;
            }
            m[(2 * rr) * n + i] = run.x;
            m[(2 * rr + 1) * n + i] = bits;
        }
    complete[i] = ok;
    atomicAdd(&counts[0], (unsigned long long)pairs);
    atomicAdd(&counts[1], (unsigned long long)cand);
}

__device__ __forceinline__ float3 kgrad(float3 d, float r, float inv_h, float l) {
    float q = r * inv_h, t = fmaxf(1.f - q, 0.f);
    float f = q <= 0.5f ? q * (3.f * q - 2.f) : -t * t;
    float s = r > 1e-9f ? l * f / r : 0.f;
    return make_float3(s * d.x, s * d.y, s * d.z);
}

// V0: the engine's layout: float4 positions, float kappa apart; the mask loop per run.
template <bool kLdg>
__global__ void accelerate(const float4* __restrict__ x, const float* __restrict__ kappa, const uint32_t* __restrict__ m,
                           float4* __restrict__ a, int n, float h, float mass) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float inv_h = 1.f / h, l = (48.f / 3.14159265f) * inv_h * inv_h * inv_h * inv_h;
    float4 xi4 = x[i];
    float ki = kappa[i];
    float3 acc = make_float3(0, 0, 0);
    for (int rr = 0; rr < 9; ++rr) {
        uint32_t s = m[(2 * rr) * n + i], bits = m[(2 * rr + 1) * n + i];
        while (bits) {
            uint32_t j = s + __ffs(bits) - 1;
            bits &= bits - 1;
            float4 xj = kLdg ? __ldg(&x[j]) : x[j];
            float kj = kLdg ? __ldg(&kappa[j]) : kappa[j];
            float3 d = make_float3(xi4.x - xj.x, xi4.y - xj.y, xi4.z - xj.z);
            float r = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
            float3 gr = kgrad(d, r, inv_h, l);
            float w = mass * (ki + kj);
            acc.x -= w * gr.x; acc.y -= w * gr.y; acc.z -= w * gr.z;
        }
    }
    a[i] = make_float4(acc.x, acc.y, acc.z, 0.f);
}

// V1: kappa packed in the position's w: one 16-byte load a neighbour.
__global__ void accelerate_packed(const float4* __restrict__ xk, const uint32_t* __restrict__ m, float4* __restrict__ a, int n, float h, float mass) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float inv_h = 1.f / h, l = (48.f / 3.14159265f) * inv_h * inv_h * inv_h * inv_h;
    float4 xi = xk[i];
    float3 acc = make_float3(0, 0, 0);
    for (int rr = 0; rr < 9; ++rr) {
        uint32_t s = m[(2 * rr) * n + i], bits = m[(2 * rr + 1) * n + i];
        while (bits) {
            uint32_t j = s + __ffs(bits) - 1;
            bits &= bits - 1;
            float4 xj = __ldg(&xk[j]);
            float3 d = make_float3(xi.x - xj.x, xi.y - xj.y, xi.z - xj.z);
            float r = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
            float3 gr = kgrad(d, r, inv_h, l);
            float w = mass * (xi.w + xj.w);
            acc.x -= w * gr.x; acc.y -= w * gr.y; acc.z -= w * gr.z;
        }
    }
    a[i] = make_float4(acc.x, acc.y, acc.z, 0.f);
}

// V2: one loop over all nine runs' bits (lanes stay busy across runs).
__global__ void accelerate_flat(const float4* __restrict__ x, const float* __restrict__ kappa, const uint32_t* __restrict__ m,
                                float4* __restrict__ a, int n, float h, float mass) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float inv_h = 1.f / h, l = (48.f / 3.14159265f) * inv_h * inv_h * inv_h * inv_h;
    float4 xi4 = x[i];
    float ki = kappa[i];
    float3 acc = make_float3(0, 0, 0);
    int rr = 0;
    uint32_t s = m[i], bits = m[n + i];
    while (true) {
        while (bits == 0 && ++rr < 9) { s = m[(2 * rr) * n + i]; bits = m[(2 * rr + 1) * n + i]; }
        if (bits == 0) break;
        uint32_t j = s + __ffs(bits) - 1;
        bits &= bits - 1;
        float4 xj = __ldg(&x[j]);
        float kj = __ldg(&kappa[j]);
        float3 d = make_float3(xi4.x - xj.x, xi4.y - xj.y, xi4.z - xj.z);
        float r = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
        float3 gr = kgrad(d, r, inv_h, l);
        float w = mass * (ki + kj);
        acc.x -= w * gr.x; acc.y -= w * gr.y; acc.z -= w * gr.z;
    }
    a[i] = make_float4(acc.x, acc.y, acc.z, 0.f);
}

// V3: the kernel gradient from one reciprocal square root (no division, no square root).
__global__ void accelerate_rsqrt(const float4* __restrict__ x, const float* __restrict__ kappa, const uint32_t* __restrict__ m,
                                 float4* __restrict__ a, int n, float h, float mass) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float inv_h = 1.f / h, l = (48.f / 3.14159265f) * inv_h * inv_h * inv_h * inv_h;
    float4 xi4 = x[i];
    float ki = kappa[i];
    float3 acc = make_float3(0, 0, 0);
    for (int rr = 0; rr < 9; ++rr) {
        uint32_t s = m[(2 * rr) * n + i], bits = m[(2 * rr + 1) * n + i];
        while (bits) {
            uint32_t j = s + __ffs(bits) - 1;
            bits &= bits - 1;
            float4 xj = __ldg(&x[j]);
            float kj = __ldg(&kappa[j]);
            float3 d = make_float3(xi4.x - xj.x, xi4.y - xj.y, xi4.z - xj.z);
            float r2 = d.x * d.x + d.y * d.y + d.z * d.z;
            float inv_r = rsqrtf(r2), q = r2 * inv_r * inv_h, t = fmaxf(1.f - q, 0.f);
            float f = q <= 0.5f ? q * (3.f * q - 2.f) : -t * t;
            float w = mass * (ki + kj) * l * f * inv_r;
            acc.x -= w * d.x; acc.y -= w * d.y; acc.z -= w * d.z;
        }
    }
    a[i] = make_float4(acc.x, acc.y, acc.z, 0.f);
}

// The residual pass's walk (correct_pressure.comp without its reduction): sum m (a_i - a_j).gradW.
__global__ void residual(const float4* __restrict__ x, const float4* __restrict__ acc_in, const uint32_t* __restrict__ m,
                         float* __restrict__ out, int n, float h, float mass) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float inv_h = 1.f / h, l = (48.f / 3.14159265f) * inv_h * inv_h * inv_h * inv_h;
    float4 xi4 = x[i], ai = acc_in[i];
    float change = 0.f;
    for (int rr = 0; rr < 9; ++rr) {
        uint32_t s = m[(2 * rr) * n + i], bits = m[(2 * rr + 1) * n + i];
        while (bits) {
            uint32_t j = s + __ffs(bits) - 1;
            bits &= bits - 1;
            float4 xj = __ldg(&x[j]), aj = __ldg(&acc_in[j]);
            float3 d = make_float3(xi4.x - xj.x, xi4.y - xj.y, xi4.z - xj.z);
            float r = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
            float3 gr = kgrad(d, r, inv_h, l);
            change += mass * ((ai.x - aj.x) * gr.x + (ai.y - aj.y) * gr.y + (ai.z - aj.z) * gr.z);
        }
    }
    out[i] = change;
}

// Bytes only: the same loads, no arithmetic but a sum (how far the arithmetic sets the time).
__global__ void loads_only(const float4* __restrict__ x, const float* __restrict__ kappa, const uint32_t* __restrict__ m, float4* __restrict__ a, int n) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    float sum = 0.f;
    for (int rr = 0; rr < 9; ++rr) {
        uint32_t s = m[(2 * rr) * n + i], bits = m[(2 * rr + 1) * n + i];
        while (bits) {
            uint32_t j = s + __ffs(bits) - 1;
            bits &= bits - 1;
            float4 xj = __ldg(&x[j]);
            sum += xj.x + xj.y + xj.z + __ldg(&kappa[j]);
        }
    }
    a[i] = make_float4(sum, 0, 0, 0);
}

template <class F>
float time_it(F f, int reps) {
    cudaEvent_t a, b;
    cudaEventCreate(&a); cudaEventCreate(&b);
    f();
    cudaEventRecord(a);
    for (int k = 0; k < reps; ++k) f();
    cudaEventRecord(b);
    cudaEventSynchronize(b);
    float ms = 0;
    cudaEventElapsedTime(&ms, a, b);
    return ms / reps;
}

// A ranryu particle export (binary little-endian PLY, every property a 4-byte float): positions, and the
// index of the "pressure" property (-1 if none) with its values.
static std::vector<float4> read_ply(const char* path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) { printf("cannot open %s\n", path); exit(1); }
    std::string line;
    long n = 0;
    int props = 0, pressure = -1;
    while (std::getline(f, line) && line != "end_header") {
        if (line.rfind("element vertex ", 0) == 0) n = atol(line.c_str() + 15);
        if (line.rfind("property ", 0) == 0) {
            if (line.find("float") == std::string::npos) { printf("%s: only float properties are read\n", path); exit(1); }
            if (line.size() >= 9 && line.compare(line.size() - 9, 9, " pressure") == 0) pressure = props;
            ++props;
        }
    }
    std::vector<float> body(size_t(n) * props);
    f.read(reinterpret_cast<char*>(body.data()), std::streamsize(body.size() * 4));
    if (!f) { printf("%s: short body\n", path); exit(1); }
    std::vector<float4> x(n);
    for (long i = 0; i < n; ++i) {
        const float* r = &body[size_t(i) * props];
        x[i] = make_float4(r[0], r[1], r[2], pressure >= 0 ? r[pressure] : 0.f);
    }
    return x;
}

int main(int argc, char** argv) {
    const bool ply = argc > 3 && strcmp(argv[1], "--ply") == 0;
    int nx = argc > 3 && !ply ? atoi(argv[1]) : 100, ny = argc > 3 && !ply ? atoi(argv[2]) : 200, nz = argc > 3 && !ply ? atoi(argv[3]) : 50;
    int block = argc > 4 ? atoi(argv[4]) : 128;
    const float dx = ply ? float(atof(argv[3])) : 0.4f / ny, h = 2 * dx, mass = 1000.f * dx * dx * dx;
    std::vector<float4> hx;
    if (ply) {
        hx = read_ply(argv[2]);
    } else {
        // The dam break's column on a jittered lattice (0.1 dx, a fixed hash), in the tank 1.0 x 0.5 x 0.1.
        hx.resize(size_t(nx) * ny * nz);
        uint32_t seed = 12345u;
        auto rnd = [&]() { seed = seed * 1664525u + 1013904223u; return (seed >> 8) * (1.f / 16777216.f) - 0.5f; };
        for (int k = 0, p = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i, ++p)
                    hx[p] = make_float4((i + 0.5f + 0.1f * rnd()) * dx, (j + 0.5f + 0.1f * rnd()) * dx, (k + 0.5f + 0.1f * rnd()) * dx, 0.f);
    }
    const int n = int(hx.size());
    Grid g;
    g.cell = h;
    g.origin = make_float3(-3 * dx, -3 * dx, -3 * dx);
    g.dims = make_int3(int((1.0f + 6 * dx) / h) + 1, int((0.5f + 6 * dx) / h) + 1, int((0.1f + 6 * dx) / h) + 1);
    const int cells = g.dims.x * g.dims.y * g.dims.z;
    float4 *x, *xs, *a, *xk; float* kappa; uint32_t *k, *idx, *m, *complete; uint2* r; unsigned long long* counts;
    CK(cudaMalloc(&x, n * 16)); CK(cudaMalloc(&xs, n * 16)); CK(cudaMalloc(&a, n * 16)); CK(cudaMalloc(&xk, n * 16));
    CK(cudaMalloc(&kappa, n * 4)); CK(cudaMalloc(&k, n * 4)); CK(cudaMalloc(&idx, n * 4));
    CK(cudaMalloc(&m, size_t(18) * n * 4)); CK(cudaMalloc(&complete, n * 4)); CK(cudaMalloc(&r, size_t(cells) * 8));
    CK(cudaMalloc(&counts, 16));
    CK(cudaMemcpy(x, hx.data(), n * 16, cudaMemcpyHostToDevice));
    int gb = (n + 255) / 256;
    keys<<<gb, 256>>>(x, k, n, g);
    thrust::sequence(thrust::device_ptr<uint32_t>(idx), thrust::device_ptr<uint32_t>(idx) + n);
    thrust::sort_by_key(thrust::device_ptr<uint32_t>(k), thrust::device_ptr<uint32_t>(k) + n, thrust::device_ptr<uint32_t>(idx));
    thrust::gather(thrust::device_ptr<uint32_t>(idx), thrust::device_ptr<uint32_t>(idx) + n, thrust::device_ptr<float4>(x), thrust::device_ptr<float4>(xs));
    CK(cudaMemset(r, 0, size_t(cells) * 8));
    ranges<<<gb, 256>>>(k, r, n);
    CK(cudaMemset(counts, 0, 16));
    masks<<<gb, 256>>>(xs, r, m, complete, counts, n, g, h);
    CK(cudaDeviceSynchronize());
    unsigned long long hc[2];
    CK(cudaMemcpy(hc, counts, 16, cudaMemcpyDeviceToHost));
    std::vector<uint32_t> hcomp(n);
    CK(cudaMemcpy(hcomp.data(), complete, n * 4, cudaMemcpyDeviceToHost));
    long incomplete = 0;
    for (uint32_t c : hcomp) incomplete += c == 0;
    // kappa: a smooth field (hydrostatic), packed copy.
    std::vector<float4> hs(n);
    CK(cudaMemcpy(hs.data(), xs, n * 16, cudaMemcpyDeviceToHost));
    std::vector<float> hk(n);
    // kappa: hydrostatic on the lattice; from the file's pressure (over rho0^2, kappa's scale) on a PLY.
    for (int i = 0; i < n; ++i) { hk[i] = ply ? hs[i].w / 1e6f : 9.81f * (0.4f - hs[i].y) / 1000.f; hs[i].w = hk[i]; }
    CK(cudaMemcpy(kappa, hk.data(), n * 4, cudaMemcpyHostToDevice));
    CK(cudaMemcpy(xk, hs.data(), n * 16, cudaMemcpyHostToDevice));
    printf("particles %d, dx %.5f, grid %d x %d x %d, pairs %llu (%.1f a particle), candidates %llu (%.1f), incomplete masks %ld, block %d\n",
           n, dx, g.dims.x, g.dims.y, g.dims.z, hc[0], double(hc[0]) / n, hc[1], double(hc[1]) / n, incomplete, block);
    int gbl = (n + block - 1) / block;
    const int reps = 50;
    float t_masks = time_it([&] { masks<<<gb, 256>>>(xs, r, m, complete, counts, n, g, h); }, 10);
    float t0 = time_it([&] { accelerate<false><<<gbl, block>>>(xs, kappa, m, a, n, h, mass); }, reps);
    float t0l = time_it([&] { accelerate<true><<<gbl, block>>>(xs, kappa, m, a, n, h, mass); }, reps);
    float t1 = time_it([&] { accelerate_packed<<<gbl, block>>>(xk, m, a, n, h, mass); }, reps);
    float t2 = time_it([&] { accelerate_flat<<<gbl, block>>>(xs, kappa, m, a, n, h, mass); }, reps);
    float t3 = time_it([&] { loads_only<<<gbl, block>>>(xs, kappa, m, a, n); }, reps);
    float t4 = time_it([&] { accelerate_rsqrt<<<gbl, block>>>(xs, kappa, m, a, n, h, mass); }, reps);
    float t5 = time_it([&] { residual<<<gbl, block>>>(xs, xk, m, kappa, n, h, mass); }, reps);
    CK(cudaGetLastError());
    auto line = [&](const char* name, float ms) { printf("%-34s %8.4f ms  %6.2f Gpairs/s\n", name, ms, hc[0] / (ms * 1e-3) / 1e9); };
    line("masks (candidate walk, 2 atomics each)", t_masks);
    line("accelerate (engine layout)", t0);
    line("accelerate, __ldg", t0l);
    line("accelerate, kappa in w", t1);
    line("accelerate, one loop over runs", t2);
    line("loads only", t3);
    line("accelerate, rsqrt", t4);
    line("residual (no reduction)", t5);
    return 0;
}
