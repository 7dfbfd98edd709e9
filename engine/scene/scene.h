#pragma once
// A scene: what to simulate and how to look at it. Scenes are JSON files (media/scenes/*.json are
// bundled into the binary); every key is known and range-checked, and any error names the file,
// the key and what is wrong (ranryu::InputError, exit code 2).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/shading.h"

namespace ranryu::scene {

// A box of particles on a cubic lattice: x = min + (i + ½)·spacing for every cell that fits.
struct Block {
    glm::vec3 min{0.0f}, max{0.0f};
    glm::vec3 velocity{0.0f};   // initial velocity (m/s)
};

// A static solid in the tank, sampled with boundary particles (docs/SPH.md eq. (8)).
struct Obstacle {
    enum class Kind { box, sphere } kind = Kind::box;
    glm::vec3 min{0.0f}, max{0.0f};   // box
    glm::vec3 center{0.0f};           // sphere
    float radius = 0.0f;
    bool contains(glm::vec3 p, float margin = 0.0f) const;
};

// What moves the particles: "ballistic" (gravity and bouncing walls only, the talk's opening
// example, docs/METHOD.md §0) or "sph" (docs/SPH.md).
enum class Model { ballistic, sph };

// The pressure solver (sim/solver.h): DFSPH (docs/DFSPH.md), WCSPH (docs/SPH.md (3)) or PBF (docs/PBF.md).
enum class Solver { dfsph, wcsph, pbf };
const char* solver_name(Solver s);
Solver parse_solver(const std::string& name, const std::string& what);   // throws InputError naming `what`

// Position Based Fluids (docs/PBF.md; Macklin & Müller 2013): a fixed number of substeps a frame and
// of constraint iterations a substep, so a frame's cost is known before it runs.
struct PbfSettings {
    int substeps = 4;               // a frame (dt = frame_dt / substeps)
    int iterations = 4;             // constraint iterations a substep, (P3)-(P6) each
    float relaxation = 0.1f;        // epsilon of (P4), in units of 1/dx^2
    float s_corr_k = 0.1f;          // k of (P5), the tensile-instability term
    int s_corr_n = 4;               // n of (P5)
    float s_corr_dq = 0.2f;         // |dq| of (P5), in units of h
    float xsph = 0.01f;             // c of (P7)
    float vorticity = 0.0f;         // epsilon of (P8) (m/s); 0: no vorticity confinement
    float warm_start = 0.0f;        // w of (P10): the last step's pressure acceleration in the prediction
    // Where `substeps` came from: the scene file's value at its particles.spacing (set by parse()).
    // with_spacing() scales from these, so that a run of spacing changes (the window's slider) ends
    // with the substeps of the last spacing, whatever the path. 0: scale from the current values.
    int reference_substeps = 0;
    float reference_spacing = 0.0f;
};

struct SphSettings {
    Solver solver = Solver::dfsph;
    float rest_density = 1000.0f;   // rho0 (kg/m^3)
    float viscosity = 1e-4f;        // kinematic nu (m^2/s), eq. (5)
    float artificial_viscosity = 0.0f;   // WCSPH: alpha of eq. (5a), on approaching pairs only
    float speed_of_sound = 0.0f;    // c (m/s) of WCSPH; 0: 10 * sqrt(2 g H), H the fluid's height
    float cfl = 0.4f;               // eq. (7), (D8)
    float dfsph_cfl = 0.0f;         // (D8): DFSPH's own Courant number in place of cfl; 0: cfl
    float force_factor = 0.25f;     // eq. (7), (D8)
    float max_time_step = 0.005f;   // (s): the largest step, also at rest (at most the frame)
    // DFSPH (docs/DFSPH.md):
    float max_density_error = 1e-3f;      // eta of (D6), a fraction of rho0
    float max_divergence_error = 1e-3f;   // eta_v of (D6)
    float max_particle_density_error = 1e-2f;   // eta_p of (D6): no particle's error above it; 0: no such bound
    int min_iterations = 2;               // density solve
    int max_iterations = 100;             // density solve
    int max_divergence_iterations = 100;
    int shrink_step_above = 20;           // (D8): a density solve of more iterations shrinks the step by 0.9; 0: off
    int grow_step_below = 10;             // (D8): one of fewer lets it grow by 1.1
    bool divergence_solve = true;         // (D5); false: the density solve alone
    float warm_start = 1.0f;              // w of (D6), the density solve's
    float divergence_warm_start = 0.5f;   // w of (D6), the divergence solve's
    float relaxation = 0.5f;              // omega of (D6)
    float chebyshev = 0.98f;              // rho of (D10)'s Chebyshev acceleration; 0: plain relaxed Jacobi
    bool complementarity_error = false;   // (D6): the density solve's error counts |r_i| where kappa_i > 0
    bool gradient_correction = false;     // (D11): pressure accelerations times the kernel-gradient correction L_i
    float pressure_stabilisation = 0.0f;  // gamma of (D12): the density solve's blend of the compact Laplacian; 0: off
    float boundary_viscosity = 0.0f;      // nu_b of (D7) (m^2/s); 0: free-slip walls
    bool boundary_rows = true;            // (D9): boundary particles as rows of the solves; false: Akinci's term
    bool eliminate_boundary_rows = false; // (D13): the density solve's rows extended from the fluid's pressure
    float boundary_relaxation = 1.0f;     // omega_b of (D9)
    bool morton = false;            // neighbour-grid keys: Morton order instead of linear
    bool neighbour_masks = true;    // the density pass records which candidates of each neighbour run lie
                                    // inside h, and forces reads that instead of testing every candidate
                                    // again (glsl/sim/fluid/density_walk.glsl; docs/PERFORMANCE.md)
    std::string sort = "radix";     // "radix" | "bitonic"
    int max_substeps = 2000;        // per frame, the most the CPU will issue (a runaway bound; the guard's dt floor stops collapse)
    float density_limit = 1.5f;     // guard: rho/rho0 bound
    float speed_limit = 0.0f;       // guard: |v| bound (m/s); 0: 5 * (sqrt(2 g H_tank) + initial speed)
    PbfSettings pbf;
    std::string why;                // sph.why: why these settings (a comment; nothing simulated reads it)

    // The Courant number of the solver's step: DFSPH's flow-speed condition (D8) takes dfsph_cfl where
    // set, WCSPH's acoustic condition (7) and every other case take cfl. The reference form lets the
    // window's panel and the sweep change the one that is in force.
    float courant() const { return solver == Solver::dfsph && dfsph_cfl > 0.0f ? dfsph_cfl : cfl; }
    float& courant() { return solver == Solver::dfsph && dfsph_cfl > 0.0f ? dfsph_cfl : cfl; }
};

// Sub-particles (docs/METHOD.md §6; engine/turbulence/subparticles.h): particles whose ê reaches
// `threshold` split into 8^L sub-particles, L = 1 + floor(log2(ê/threshold) / (2β)) up to `levels`.
// levels = 0 (the default): nothing is built and no pass runs.
struct SubparticleSettings {
    int levels = 0;                 // L_max, the finest level (0..3); 0: no sub-particles
    float threshold = 0.01f;        // e_th (m²/s²): the ê at which a particle splits to level 1
    int budget = 1 << 22;           // most sub-particles a frame holds; above it the finest levels are dropped
    bool enabled() const { return levels > 0; }
};

// The turbulence force (docs/METHOD.md §5; engine/turbulence/force.h): off unless amplitude > 0, and
// then only with model "sph". With amplitude 0 nothing is constructed and no pass runs.
struct TurbulenceSettings {
    float amplitude = 0.0f;           // A (1/m): the force per unit mass is A·ê·y (force.h)
    float scale = 1.0f / 3.0f;        // wavelet scale s in units of h (at most 1/3: s·3 <= the grid cell h)
    int lmin = 3, lmax = 5;           // noise octaves (octave i: wavelengths of about 2..4 · 2^-i m)
    float beta = 1.0f / 3.0f;         // octave falloff 2^(-β(i - lmin)); 1/3: E(k) ∝ k^(-5/3)
    std::uint32_t seed = 1;           // noise tiles' seed
    // The noise is carried with the fluid (glsl/turbulence/carried_noise.glsl): each particle's noise
    // coordinates are re-seeded every `coherence_time`, in two phases half a period apart.
    float coherence_time = 0.5f;      // T (s)
    SubparticleSettings subparticles;
    bool enabled() const { return amplitude > 0.0f; }
};

// The liquid surface (engine/surface/): the level set grid and the mesh capacity, and the water's
// absorption in the Fresnel and water shading modes. Used only when the shading draws a surface.
struct SurfaceSettings {
    float node_spacing = 0.5f;           // φ-grid node spacing, in particle spacings
    int max_dims = 512;                  // most φ-grid nodes per axis (a larger box coarsens the grid)
    int max_nodes = 1 << 23;             // most φ-grid nodes in all (docs/SURFACE.md (S9))
    bool anisotropic = true;             // Yu & Turk's anisotropic kernels (docs/SURFACE.md)
    int max_vertices = 1 << 22;          // mesh capacity (3 per triangle; more are dropped)
    // Beer-Lambert sigma per channel (1/m): pure water's, scaled (render/shading.h); red fades first.
    glm::vec3 absorption = float(RANRYU_WATER_ABSORPTION_SCALE) * glm::vec3(RANRYU_WATER_ABSORPTION_PURE);
};

struct Scene {
    std::string name;          // file stem, or "name" key
    std::string description;
    std::string origin;        // where it came from: "bundled" or the file path
    std::string source;        // the JSON text parse() read (a checkpoint rebuilds the scene from it)

    // Tank: the axis-aligned box the fluid lives in (m). Walls reflect with `restitution`.
    glm::vec3 tank_min{0.0f}, tank_max{1.0f};
    bool tank_closed = false;   // SPH: a lid at tank_max.y, sampled with boundary particles like the walls
    float restitution = 0.5f;
    glm::vec3 gravity{0.0f, -9.81f, 0.0f};

    // Time: each frame advances `frame_dt` of simulated time in ceil(frame_dt / substep_dt) substeps.
    float frame_dt = 1.0f / 60.0f;
    float substep_dt = 1.0f / 480.0f;

    float spacing = 0.02f;          // particle spacing (m): the resolution
    float particle_radius = 0.01f;  // drawn radius (m); default spacing / 2
    std::vector<Block> blocks;
    std::vector<Obstacle> obstacles;
    // The paddle (not a scene key: `ranryu run` sets it): a kinematic sphere of this radius (m) that
    // the window drags through the liquid, 0 for none (sim/boundary.h paddle_offsets(), sim::Fluid::move_paddle).
    float paddle_radius = 0.0f;
    // The emitter's budget (not a scene key: `ranryu run` sets it): particles allocated, the scene's
    // and parked ones the emitter can pour in (sim/fluid.h). At most particle_count() is none to pour.
    std::size_t particle_budget = 0;

    Model model = Model::ballistic;
    SphSettings sph;
    SurfaceSettings surface;
    TurbulenceSettings turbulence;

    glm::vec3 camera_eye{2.0f, 1.5f, 2.5f};
    glm::vec3 camera_target{0.5f, 0.3f, 0.3f};
    float fov_deg = 40.0f;
    glm::vec3 light_dir{0.4f, 1.0f, 0.3f};   // toward the light; normalised on load
    float ambient = 0.25f;

    int width = 960, height = 540;   // default image size; --size overrides

    int substeps() const;
    float fluid_height() const;        // highest block top above the tank floor (m)
    float speed_estimate() const;      // sqrt(2 g H_tank) + the largest initial speed (m/s)
    float sound_speed() const;         // WCSPH: sph.speed_of_sound, or 10 sqrt(2 g H) (docs/SPH.md); 0 for DFSPH
    // Particle positions on the lattice of every block, in block order, less those inside obstacles.
    std::vector<glm::vec4> initial_positions() const;
    std::vector<glm::vec4> initial_velocities() const;
    // ρ0·|g|·(top − y) for each initial particle of a block at rest on the tank's floor (the pressure
    // of the block at rest under gravity), 0 for the others: an incompressible solver's first guess.
    std::vector<float> initial_pressures() const;
    std::size_t particle_count() const;
    std::size_t particle_capacity() const;   // max(particle_count(), particle_budget): what is allocated
};

// Parses and validates JSON text. `origin` names the input in error messages.
Scene parse(const std::string& json_text, const std::string& origin);

// `name_or_path`: a bundled scene's name ("falling-block") or a path to a .json file.
Scene load(const std::string& name_or_path);

// The same scene at another resolution: particle spacing `dx` (m), radius dx/2, PBF's substeps scaled
// by the old spacing over dx, rounded up (its step keeps its Courant number, docs/PBF.md). Throws
// ranryu::InputError (naming `what`) when that leaves no particle or too many.
Scene with_spacing(Scene s, float dx, const std::string& what);

// A bundled data file (media/validation/*.csv), by its path under media/.
std::string bundled_file(const std::string& path);

struct BundledScene {
    std::string name;
    std::string description;
    std::string why;   // its sph.why, "" when it has none
};
std::vector<BundledScene> bundled();

}  // namespace ranryu::scene
