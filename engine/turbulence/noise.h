#pragma once
// Turbulence synthesis (docs/METHOD.md §4): band-limited wavelet noise (Cook & DeRose 2005) as a vector
// potential N = (N1, N2, N3), its curl w = ∇×N, and the octave sum
//
//     y(x) = Σ_{i=lmin}^{lmax} w(2^i x + o_i) · 2^(−β (i − lmin))
//
// Tiles: three independent n³ periodic tiles (one per potential component), made on the CPU at
// start-up from one seed (std::mt19937, deterministic), uploaded once. Each tile is Cook & DeRose's
// construction: Gaussian random values R, downsample (their 32-tap analysis filter) then upsample
// (the quadratic B-spline refinement filter 1/4, 3/4, 3/4, 1/4) along x, y, z, and N = R − upsampled:
// what the coarse level cannot represent, a band of about [k_N/2, k_N] (k_N the tile's Nyquist); then
// the odd-offset copy is added to even out the variance of even and odd cells. N is evaluated as a
// quadratic B-spline with the tile values as coefficients (not an interpolating spline), so N is C¹.
//
// Curl: the exact (analytic) curl of that B-spline, from the derivatives of the B-spline weights
// (glsl/turbulence/curl_noise.glsl). It is divergence-free as a function; checked with central
// differences on a grid of spacing h it shows a truncation error of order (k·h)² (docs/METHOD.md §4).
//
// Units: x in metres; one tile cell of octave 0 is 1 m, so octave i has cells of 2^−i m and its band
// holds wavelengths of about 2·2^−i to 4·2^−i m. The tiles repeat every n·2^−i m. o_i is a fixed
// per-octave offset (noise units) so that the octaves, which share the tiles, are not aligned.
// w is the curl in noise coordinates (∇_q × N at q = 2^i x + o_i), as in the formula above: no 2^i
// factor, so octave i carries energy ∝ 2^(−2β(i − lmin)).
//
// Spectrum convention: Kolmogorov's law on the shell-averaged spectral density, E(k) ∝ k^(−5/3).
// Octave i spreads energy 2^(−2β(i−lmin)) over a band of width ∝ 2^i, so E(k) ∝ k^(−1−2β): β = 1/3
// gives −5/3 (the default). β = 5/6 (Kim et al. 2008: energy *per octave* ∝ k^(−5/3)) gives −8/3.
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"

namespace ranryu::turbulence {

constexpr float kKolmogorovBeta = 1.0f / 3.0f;   // E(k) ∝ k^(−1−2β) = k^(−5/3)
constexpr int kDefaultTileSize = 32;

// One band-limited wavelet-noise tile of n³ values (n even, ≥ 8), index x + n·(y + n·z), periodic.
std::vector<float> wavelet_tile(int n, std::mt19937& rng);

// The three potential tiles from one seed: tile c drawn after tile c−1 from the same std::mt19937.
struct NoiseTiles {
    int n = 0;
    std::array<std::vector<float>, 3> tile;
    static NoiseTiles generate(std::uint32_t seed, int n = kDefaultTileSize);
};

// Per-octave offset o_i (noise units), as in glsl/turbulence/curl_noise.glsl.
glm::vec3 octave_offset(int i);

// CPU references of glsl/turbulence/curl_noise.glsl (tests): w(q) = ∇_q × N(q), and the octave sum y(x).
glm::vec3 curl_noise(const NoiseTiles& tiles, glm::vec3 q);
glm::vec3 curl_noise_octaves(const NoiseTiles& tiles, glm::vec3 x, int lmin, int lmax, float beta);

// The noise carried with the fluid (glsl/turbulence/carried_noise.glsl states the scheme), CPU
// references (tests): the per-epoch offset o(m) (m), phase p's epoch at t, the re-seeding of the
// phases whose epoch changed (s_p = x and the phase's value y(q_p)), and y_c at offset d (m) from the
// seeded positions.
glm::vec3 epoch_offset(float m, int n, int lmin);
float noise_epoch(int p, float t, float period);
gpu::NoiseSeed reseed_noise(const NoiseTiles& tiles, gpu::NoiseSeed s, glm::vec3 x, float t, float period, int lmin, int lmax,
                            float beta);
glm::vec3 carried_noise(const NoiseTiles& tiles, const gpu::NoiseSeed& s, glm::vec3 d, float t, float period, int lmin,
                        int lmax, float beta);
// Seeds that no epoch matches (w = −1): the first re-seeding sets every phase.
gpu::NoiseSeed unseeded_noise();

// A regular grid of points origin + spacing·(i, j, k), 0 ≤ i, j, k < dims, and the octave sum.
struct FieldSpec {
    glm::uvec3 dims{64u};
    glm::vec3 origin{0.0f};
    float spacing = 1.0f / 64.0f;   // (m)
    int lmin = 2, lmax = 4;
    float beta = kKolmogorovBeta;
    std::size_t points() const { return std::size_t(dims.x) * dims.y * dims.z; }
};

// The noise on the GPU: the tiles in one buffer (storage block NoiseTiles) and the sampling pass
// "noise.sample" (glsl/turbulence/sample_field.comp).
class CurlNoise {
public:
    CurlNoise(const shader::FileSource& shaders, profile::GpuTimer& timer, const NoiseTiles& tiles);
    // Device memory the constructor allocates for tiles of n³ (frame/memory.h).
    static std::size_t bytes_for(int n) { return 3 * std::size_t(n) * n * n * sizeof(float) + sizeof(gpu::NoiseParams); }
    int tile_size() const { return n_; }
    const gl::Buffer& tiles() const { return tiles_; }

    // Samples y on `spec`'s grid into `out` (float[points·3], point (i, j, k) at ((i·ny + j)·nz + k)·3:
    // C order of shape (nx, ny, nz, 3)). `out` must hold that many floats. Runs inside a timer frame.
    void sample(const FieldSpec& spec, gl::Buffer& out);
    // Allocates the output, samples, reads it back (tests and tools).
    std::vector<float> sample_to_host(const FieldSpec& spec);

private:
    profile::GpuTimer& timer_;
    profile::PassId pass_;
    shader::Program program_;
    gl::Buffer tiles_;
    gl::Buffer params_;
    int n_ = 0;
};

}  // namespace ranryu::turbulence
