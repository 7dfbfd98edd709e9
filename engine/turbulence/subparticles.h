#pragma once
// Sub-particles: the turbulence below the particle scale (docs/METHOD.md §6; docs/SUBPARTICLES.md has the
// whole story). After the SPH substeps of a frame, every particle whose wavelet energy ê_i (m²/s²,
// wavelet.h) reaches the threshold e_th is drawn and meshed as 8^E smaller particles that carry the
// finer octaves of the curl noise; the others stay as they are.
//
// Levels. Per octave the noise's energy falls by 2^(-2β) (its amplitude by 2^(-β), noise.h): with
// β = 1/3, the spectral density falls as E(k) ∝ k^(-5/3) (Kolmogorov, noise.h's convention). The
// energy E levels below the particle is then e_E = ê·2^(-2βE), and a particle splits as far as the
// level above the finest one still holds at least e_th:
//
//     L_i = 0                                                if ê_i < e_th
//     L_i = min(L_max, 1 + floor(log2(ê_i/e_th) / (2β)))     otherwise
//
// i.e. L_i - 1 is the largest k with ê_i·2^(-2βk) >= e_th. The paper's e_crit(L) = ê·2^(-5L/3)
// (docs/METHOD.md §6) is the same rule in the convention where the energy *per octave* falls as
// k^(-5/3), β = 5/6 (2β = 5/3); here β is the scene's, the one the force's noise uses, so
// sub-particles continue the same spectrum.
// On the GPU L_i is counted as the thresholds ê_i reaches, level_energy[k] = e_th·2^(2βk) (the same
// rule, exact comparisons: the CPU's count from the same ê is the GPU's to the particle).
//
// Budget. With n_L particles at raw level L, the cap C is the largest C <= L_max with
// Σ_{L>=1} n_L·8^min(L,C) <= budget (C = 0: nothing splits); particle i splits to E_i = min(L_i, C).
// Dropping the finest levels first keeps every energetic particle split (a coarser picture of the
// same flow) rather than some fully and others not at all.
//
// Passes (named in the GpuTimer), every one on the GPU, nothing read back in the frame path:
//   "subparticles.classify"  classify_particles.comp      L_i per particle; per-workgroup level counts
//   "subparticles.scan"      scan_level_counts.comp       one workgroup: their exclusive scan; n_L
//   "subparticles.compact"   compact_split_particles.comp per-level lists of the particles with L_i >= 1,
//                                                          in cell order (scan, no atomics: the same
//                                                          lists, sub-particle order and images every run)
//   "subparticles.budget"    choose_level_cap.comp        one invocation: C, the layout, the indirect
//                                                          dispatch and draw arguments; queues the stats
//   "subparticles.spawn"     spawn_subparticles.comp      one invocation per sub-particle (indirect)
// and, in the level set (surface/level_set.h), "subparticles.splat".
//
// Children (spawn_subparticle() below is the CPU reference): parent p at x_p, spacing dx, level E has
// 8^E children c at the centres of the 8^E sub-cubes of its cell, o_c = Σ_{l=1..E} (dx/2^l)(b_l - ½)
// with b_l ∈ {0,1}³ the l-th base-8 digit of c (l = 1 the lowest; bits x, y, z), and
//
//     ŷ_c = y_c(seed_p, o_c, t; octave lmax + E) / σ         v_c = v_p + √(2 e_E)·ŷ_c
//     x_c = x_p + o_c + ½(dx/2^E)·ŷ_c                         stored: (x_c, E), (v_c, e_E)
//
// y_c is the noise carried with the fluid (glsl/turbulence/carried_noise.glsl) from the parent's own
// seeds, sampled at the child's lattice offset, one octave: lmax + E, the first octave below the
// force's that level E resolves. σ is the rms of |w| over one octave (octave_rms(), measured once on
// the CPU from the tiles), so ŷ has unit rms and ½|v_c - v_p|² averages e_E. The displacement moves a
// child by about half its own spacing along the same noise.
// Why stateless: the set of energetic particles and the parents' order change every substep (the
// neighbour sort reorders them; ê rises and falls), so sub-particles kept from frame to frame would
// need to be matched to parents again each frame. Instead a child is a pure function of its parent's
// state and seeds, c, E and t: the seeds are integrated with the fluid (the reorder carries them, the
// force pass re-seeds them every T with the epoch blend), so y_c, and with it every child's position
// and velocity, changes smoothly in time while its parent stays at the same level. A child appears or
// vanishes when its parent's level changes; its parent's volume is conserved across that (the level
// set gives each child V/8^E).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/readback.h"
#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "turbulence/noise.h"

namespace ranryu::sim { class Fluid; }
namespace ranryu::turbulence { class TurbulenceForce; }

namespace ranryu::turbulence {

constexpr int kMaxSubparticleLevel = RANRYU_SUBPARTICLE_MAX_LEVEL;

// level_energy[k] = e_th·2^(2βk) for k < levels, +inf beyond (x, y, z: k = 0, 1, 2; w unused).
glm::vec4 level_energies(float threshold, float beta, int levels);
// The raw level of ê: how many of the thresholds it reaches, at most `levels` (classify_particles.comp).
int raw_level(float e, const glm::vec4& level_energy, int levels);
// e_E / ê = 2^(-2βE) for E = 1, 2, 3 (x, y, z).
glm::vec4 energy_scales(float beta);

// The cap and layout of choose_level_cap.comp, in 64 bits (the GPU saturates at 2^32 - 1).
struct LevelCap {
    int cap = 0;                 // C
    int finest = 0;              // the raw finest level: the largest L with n_L > 0
    std::uint64_t total = 0;     // sub-particles: Σ n_L·8^min(L, C), 0 when C = 0
    std::uint64_t wanted = 0;    // Σ n_L·8^L: what the raw levels would need
};
LevelCap choose_level_cap(const std::array<std::uint64_t, 3>& counts, int levels, std::uint64_t budget);

// σ: the rms of |w| = |∇×N| over one octave, from a deterministic 64³ sample of the tiles (two
// points per tile cell and axis at the 2-point Gauss positions, which integrate the piecewise
// polynomial |w|² to within a fraction of a percent).
float octave_rms(const NoiseTiles& tiles);

// o_c of child c at level E for parent spacing dx (spawn_subparticles.comp, lattice_offset).
glm::vec3 lattice_offset(std::uint32_t child, int level, float dx);

struct Subparticle {
    glm::vec4 position;   // xyz (m), w = E
    glm::vec4 velocity;   // xyz (m/s), w = e_E (m²/s²)
};
// CPU reference of spawn_subparticles.comp for one child: parent position x, velocity v, energy ê,
// seeds, child c at effective level E >= 1, time t (s), the pass's constants `p`.
Subparticle spawn_subparticle(const NoiseTiles& tiles, const gpu::SubparticleParams& p, glm::vec3 x, glm::vec3 v, float e,
                              const gpu::NoiseSeed& seed, std::uint32_t child, int level, float t);

// What the budget did, from the records that came back (frames late).
struct SubparticleStats {
    std::uint64_t frames = 0;           // records counted
    std::uint64_t dropped_frames = 0;   // records in which C < the raw finest level
    int lowest_cap = kMaxSubparticleLevel;   // the smallest C among them
    int finest_wanted = 0;              // the largest raw finest level among them
    std::uint64_t most = 0;             // the most sub-particles in a frame
    std::uint32_t budget = 0;
    std::optional<gpu::SubparticleState> last;
};
// "" when the budget never dropped a level; else e.g. "sub-particles: budget 4096 exceeded in 3 of 10
// frames, finest level dropped to 1 (levels up to 3 wanted)".
std::string budget_note(const SubparticleStats& s);

class Subparticles {
public:
    // The buffers' layout for `particles` parents: up to min(budget, particles·8^levels) sub-particles.
    // `tiles` and `noise` must be the force's (TurbulenceForce::tiles() and noise(), which must outlive
    // this): the seeds index the same field, and the spawn pass binds noise's GPU tiles. Throws
    // InputError on levels outside 1..3 or a non-positive spacing.
    Subparticles(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::TurbulenceSettings& settings,
                 float spacing, std::size_t particles, const NoiseTiles& tiles, const CurlNoise& noise);
    // Device memory the constructor allocates for `particles` parents (frame/memory.h).
    static std::size_t bytes_for(const scene::SubparticleSettings& s, std::size_t particles);
    Subparticles(const Subparticles&) = delete;   // the stats' readback calls back into this object
    Subparticles& operator=(const Subparticles&) = delete;

    // The parents, all in one (cell) order, and the StepState whose time the noise is read at.
    struct Inputs {
        const gl::Buffer& positions;    // vec4[count]: xyz (m)
        const gl::Buffer& velocities;   // vec4[count]: xyz (m/s)
        const gl::Buffer& energy;       // vec4[count]: (û, ê), WaveletAnalysis::energy()
        const gl::Buffer& seeds;        // gpu::NoiseSeed[count], TurbulenceForce::noise_seeds()
        const gl::Buffer& step;         // gpu::StepState
        std::size_t count;
    };
    // The three passes for `frame` (the stats' tag). Runs inside a GpuTimer frame; ends with the
    // barriers that let the level set read, the renderer draw and the indirect commands use the
    // results. Allocates, compiles and reads back nothing.
    void generate(const Inputs& in, std::uint64_t frame);
    // The same from the fluid's state after its last step, with the force's energy and seeds.
    void generate(const sim::Fluid& fluid, const TurbulenceForce& force, std::uint64_t frame);

    const gl::Buffer& positions() const { return positions_; }    // vec4[capacity()]: (x_c, E)
    const gl::Buffer& velocities() const { return velocities_; }  // vec4[capacity()]: (v_c, e_E)
    const gl::Buffer& state() const { return state_; }            // gpu::SubparticleState; the indirect buffer
    const gl::Buffer& levels() const { return levels_; }          // uint[particles]: L_i | E_i << 8
    const gl::Buffer& lists() const { return lists_; }            // uint[levels · particles]
    static constexpr std::size_t dispatch_offset = offsetof(gpu::SubparticleState, dispatch);
    static constexpr std::size_t draw_offset = offsetof(gpu::SubparticleState, draw);
    std::size_t capacity() const { return capacity_; }
    std::size_t max_particles() const { return max_particles_; }
    const gpu::SubparticleParams& params() const { return params_; }
    int levels_max() const { return int(params_.levels); }
    // spawn_subparticles.comp's local size: the workgroups of state().dispatch are this many wide.
    GLuint dispatch_group() const { return spawn_.local_size()[0]; }

    // Stats: collects the records that have arrived (never waits) / waits for all (end of a run).
    void poll() { readback_.poll(); }
    void drain() { readback_.drain(); }
    // Counts only records of frames >= `frame` from now on (e.g. after warm-up), forgetting the rest.
    void count_from(std::uint64_t frame);
    const SubparticleStats& stats() const { return stats_; }

private:
    void on_record(std::uint64_t frame, const void* bytes);

    profile::GpuTimer& timer_;
    profile::PassId classify_pass_, scan_pass_, compact_pass_, budget_pass_, spawn_pass_;
    shader::Program classify_, scan_, compact_, budget_, spawn_;
    const CurlNoise& noise_;   // the force's tiles on the GPU
    gpu::SubparticleParams params_{};
    std::size_t max_particles_, capacity_;
    // The buffers' sizes (bytes) for `particles` parents in workgroups of `group`.
    struct Sizes {
        std::size_t levels, blocks, lists, children;
    };
    static std::size_t capacity_for(const scene::SubparticleSettings& s, std::size_t particles);
    static Sizes sizes(const scene::SubparticleSettings& s, std::size_t particles, std::size_t group);
    gl::Buffer params_ubo_, state_, levels_, blocks_, lists_, positions_, velocities_;
    gl::AsyncReadback readback_;
    SubparticleStats stats_;
    std::uint64_t count_from_ = 0;
};

}  // namespace ranryu::turbulence
