#include "turbulence/noise.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace ranryu::turbulence {
namespace {

int wrap(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
}

// Cook & DeRose 2005, appendix: the analysis (downsampling) filter, radius 16, and the quadratic
// B-spline refinement (upsampling) filter. The paper's loop runs k up to 2i + 16 inclusive, one past
// the 32 coefficients; here k runs over the 32 coefficients only.
constexpr int kRadius = 16;
constexpr float kDown[2 * kRadius] = {
    0.000334f, -0.001528f, 0.000410f,  0.003545f,  -0.000938f, -0.008233f, 0.002172f,  0.019120f,
    -0.005040f, -0.044412f, 0.011655f, 0.103311f,  -0.025936f, -0.243780f, 0.033979f,  0.655340f,
    0.655340f,  0.033979f, -0.243780f, -0.025936f, 0.103311f,  0.011655f,  -0.044412f, -0.005040f,
    0.019120f,  0.002172f, -0.008233f, -0.000938f, 0.003546f,  0.000410f,  -0.001528f, 0.000334f};

// n values at from[0], from[stride], ... -> n/2 coarse values.
void downsample(const float* from, float* to, int n, int stride) {
    for (int i = 0; i < n / 2; ++i) {
        float s = 0.0f;
        for (int k = 2 * i - kRadius; k < 2 * i + kRadius; ++k) s += kDown[k - 2 * i + kRadius] * from[wrap(k, n) * stride];
        to[i * stride] = s;
    }
}

// n/2 coarse values -> n fine values.
void upsample(const float* from, float* to, int n, int stride) {
    constexpr float p[4] = {0.25f, 0.75f, 0.75f, 0.25f};   // p[i − 2k + 2]
    for (int i = 0; i < n; ++i) {
        float s = 0.0f;
        for (int k = i / 2; k <= i / 2 + 1; ++k) s += p[i - 2 * k + 2] * from[wrap(k, n / 2) * stride];
        to[i * stride] = s;
    }
}

}  // namespace

std::vector<float> wavelet_tile(int n, std::mt19937& rng) {
    if (n < 8 || n % 2 != 0 || n > 256) throw Error("wavelet_tile: tile size " + std::to_string(n) + " must be even, in [8, 256]");
    const std::size_t count = std::size_t(n) * n * n;
    std::vector<float> noise(count), t1(count), t2(count);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    for (float& v : noise) v = gauss(rng);
    // Downsample then upsample along x, then y, then z: the part the coarser level represents.
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y) {
            const std::size_t i = std::size_t(n) * (y + std::size_t(n) * z);
            downsample(&noise[i], &t1[i], n, 1);
            upsample(&t1[i], &t2[i], n, 1);
        }
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x) {
            const std::size_t i = x + std::size_t(n) * n * z;
            downsample(&t2[i], &t1[i], n, n);
            upsample(&t1[i], &t2[i], n, n);
        }
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const std::size_t i = x + std::size_t(n) * y;
            downsample(&t2[i], &t1[i], n, n * n);
            upsample(&t1[i], &t2[i], n, n * n);
        }
    for (std::size_t i = 0; i < count; ++i) noise[i] -= t2[i];
    // Even out the variance of even and odd cells: add a copy shifted by an odd offset.
    int offset = n / 2;
    if (offset % 2 == 0) ++offset;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                t1[x + std::size_t(n) * (y + std::size_t(n) * z)] =
                    noise[wrap(x + offset, n) + std::size_t(n) * (wrap(y + offset, n) + std::size_t(n) * wrap(z + offset, n))];
    for (std::size_t i = 0; i < count; ++i) noise[i] += t1[i];
    return noise;
}

NoiseTiles NoiseTiles::generate(std::uint32_t seed, int n) {
    NoiseTiles t;
    t.n = n;
    std::mt19937 rng(seed);
    for (auto& tile : t.tile) tile = wavelet_tile(n, rng);
    return t;
}

glm::vec3 octave_offset(int i) {
    // Keep in step with octave_offset() in glsl/turbulence/curl_noise.glsl.
    const float fi = float(i);
    return glm::vec3(glm::fract(fi * 0.6180340f), glm::fract(fi * 0.7548777f), glm::fract(fi * 0.5698403f)) * 17.0f;
}

glm::vec3 curl_noise(const NoiseTiles& tiles, glm::vec3 q) {
    const int n = tiles.n;
    const glm::vec3 midf = glm::ceil(q - 0.5f);
    const glm::vec3 t = midf - (q - 0.5f);
    const glm::vec3 w0 = 0.5f * t * t, w2 = 0.5f * (1.0f - t) * (1.0f - t), w1 = 1.0f - w0 - w2;
    const glm::vec3 W[3] = {w0, w1, w2}, D[3] = {-t, 2.0f * t - 1.0f, 1.0f - t};
    const glm::ivec3 mid(midf);
    glm::vec3 g[3] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    for (int fz = 0; fz < 3; ++fz)
        for (int fy = 0; fy < 3; ++fy)
            for (int fx = 0; fx < 3; ++fx) {
                const std::size_t c = wrap(mid.x + fx - 1, n) + std::size_t(n) * (wrap(mid.y + fy - 1, n) + std::size_t(n) * wrap(mid.z + fz - 1, n));
                const glm::vec3 d(D[fx].x * W[fy].y * W[fz].z, W[fx].x * D[fy].y * W[fz].z, W[fx].x * W[fy].y * D[fz].z);
                for (int k = 0; k < 3; ++k) g[k] += tiles.tile[k][c] * d;
            }
    return {g[2].y - g[1].z, g[0].z - g[2].x, g[1].x - g[0].y};
}

glm::vec3 curl_noise_octaves(const NoiseTiles& tiles, glm::vec3 x, int lmin, int lmax, float beta) {
    glm::vec3 y(0.0f);
    for (int i = lmin; i <= lmax; ++i)
        y += curl_noise(tiles, std::exp2(float(i)) * x + octave_offset(i)) * std::exp2(-beta * float(i - lmin));
    return y;
}

glm::vec3 epoch_offset(float m, int n, int lmin) {
    // Keep in step with epoch_offset() in glsl/turbulence/carried_noise.glsl.
    return glm::fract(m * glm::vec3(0.7548777f, 0.5698403f, 0.6180340f) + glm::vec3(0.1f, 0.3f, 0.7f)) *
           (float(n) * std::exp2(-float(lmin)));
}

float noise_epoch(int p, float t, float period) { return std::floor(t / period + 0.5f * float(p)); }

gpu::NoiseSeed reseed_noise(const NoiseTiles& tiles, gpu::NoiseSeed s, glm::vec3 x, float t, float period, int lmin, int lmax,
                            float beta) {
    for (int p = 0; p < 2; ++p) {
        const float k = noise_epoch(p, t, period);
        if (s.phase[p].w != k) {
            s.phase[p] = glm::vec4(x, k);
            s.value[p] = glm::vec4(curl_noise_octaves(tiles, x + epoch_offset(2.0f * k + float(p), tiles.n, lmin), lmin, lmax, beta), 0.0f);
        }
    }
    return s;
}

glm::vec3 carried_noise(const NoiseTiles& tiles, const gpu::NoiseSeed& s, glm::vec3 d, float t, float period, int lmin,
                        int lmax, float beta) {
    glm::vec3 y(0.0f);
    float norm = 0.0f;
    for (int p = 0; p < 2; ++p) {
        float w = std::sin(3.14159265f * glm::fract(t / period + 0.5f * float(p)));
        w *= w;
        norm += w * w;
        if (w > 0.0f) {
            const glm::vec3 q = glm::vec3(s.phase[p]) + epoch_offset(2.0f * s.phase[p].w + float(p), tiles.n, lmin) + d;
            y += w * curl_noise_octaves(tiles, q, lmin, lmax, beta);
        }
    }
    return y / std::sqrt(norm);
}

gpu::NoiseSeed unseeded_noise() {
    gpu::NoiseSeed s{};
    s.phase[0] = s.phase[1] = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
    s.value[0] = s.value[1] = glm::vec4(0.0f);
    return s;
}

CurlNoise::CurlNoise(const shader::FileSource& shaders, profile::GpuTimer& timer, const NoiseTiles& tiles)
    : timer_(timer),
      pass_(timer.pass("noise.sample")),
      program_(shader::Program::compute(shaders, "turbulence/sample_field.comp")),
      params_(sizeof(gpu::NoiseParams), GL_DYNAMIC_DRAW, nullptr, "NoiseParams"),
      n_(tiles.n) {
    const std::size_t per = std::size_t(n_) * n_ * n_;
    std::vector<float> all;
    all.reserve(3 * per);
    for (const auto& t : tiles.tile) {
        if (t.size() != per) throw Error("CurlNoise: a tile does not hold n^3 values");
        all.insert(all.end(), t.begin(), t.end());
    }
    tiles_ = gl::Buffer::from(std::span<const float>(all), GL_STATIC_DRAW, "noise.tiles");
}

void CurlNoise::sample(const FieldSpec& spec, gl::Buffer& out) {
    if (out.size() < spec.points() * 3 * sizeof(float)) throw Error("CurlNoise::sample: output buffer too small");
    gpu::NoiseParams p{};
    p.origin = glm::vec4(spec.origin, spec.spacing);
    p.dims = glm::uvec4(spec.dims, std::uint32_t(spec.points()));
    p.lmin = spec.lmin;
    p.lmax = spec.lmax;
    p.beta = spec.beta;
    p.tile_size = std::uint32_t(n_);
    params_.upload_value(p);
    auto pass = timer_.scope(pass_);
    params_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_NOISE);
    program_.bind({{"NoiseTiles", &tiles_}, {"NoiseField", &out}}).use();
    const auto ls = program_.local_size();
    glDispatchCompute((spec.dims.x + ls[0] - 1) / ls[0], (spec.dims.y + ls[1] - 1) / ls[1], (spec.dims.z + ls[2] - 1) / ls[2]);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::vector<float> CurlNoise::sample_to_host(const FieldSpec& spec) {
    gl::Buffer out(spec.points() * 3 * sizeof(float), GL_DYNAMIC_COPY, nullptr, "noise.field");   // read through a staging copy
    timer_.begin_frame();
    sample(spec, out);
    timer_.end_frame();
    return out.read<float>(spec.points() * 3);
}

}  // namespace ranryu::turbulence
