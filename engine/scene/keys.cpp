#include "scene/keys.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <sstream>

#include "scene/scene.h"

namespace ranryu::scene {
namespace {

using nlohmann::json;

// A float default as the shortest decimal that reads back as the same float (1e-4f, not
// 9.99999974737875e-05): what the docs show, and what parse() turns back into that float.
double shortest(float f) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, f);
    return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
}
json vec(glm::vec3 v) { return json::array({shortest(v.x), shortest(v.y), shortest(v.z)}); }

// Builders, one per type: path, unit, default, bounds, meaning.
Key object(std::string path, std::string meaning, bool required = false) {
    return {std::move(path), KeyType::object, "", nullptr, "", 0, 0, {}, required, "", std::move(meaning)};
}
Key objects(std::string path, std::string meaning, bool required = false) {
    return {std::move(path), KeyType::objects, "", nullptr, required ? "" : "none", 0, 0, {}, required, "", std::move(meaning)};
}
Key number(std::string path, std::string unit, float def, double lo, double hi, std::string meaning) {
    return {std::move(path), KeyType::number, std::move(unit), shortest(def), "", lo, hi, {}, false, "", std::move(meaning)};
}
Key integer(std::string path, std::string unit, long long def, double lo, double hi, std::string meaning) {
    return {std::move(path), KeyType::integer, std::move(unit), def, "", lo, hi, {}, false, "", std::move(meaning)};
}
Key boolean(std::string path, bool def, std::string meaning) {
    return {std::move(path), KeyType::boolean, "", def, "", 0, 0, {}, false, "", std::move(meaning)};
}
Key string(std::string path, json def, std::vector<std::string> choices, std::string meaning) {
    return {std::move(path), KeyType::string, "", std::move(def), "", 0, 0, std::move(choices), false, "", std::move(meaning)};
}
Key vec3(std::string path, std::string unit, glm::vec3 def, double lo, double hi, std::string meaning) {
    return {std::move(path), KeyType::vec3, std::move(unit), vec(def), "", lo, hi, {}, false, "", std::move(meaning)};
}
// Modifiers: a default computed at parse time, a key that must be given, the kind of item it belongs to.
Key computed(Key k, std::string note) {
    k.def = nullptr;
    k.default_note = std::move(note);
    return k;
}
Key required(Key k) {
    k.def = nullptr;
    k.required = true;
    return k;
}
Key of_kind(Key k, std::string variant) {
    k.variant = std::move(variant);
    return k;
}

std::vector<Key> make_keys() {
    // The defaults are those of the structs in scene.h: a default Scene is what a file that sets
    // nothing gets.
    const Scene d;
    const SphSettings& h = d.sph;
    const TurbulenceSettings& u = d.turbulence;
    const SurfaceSettings& f = d.surface;
    return {
        computed(string("$schema", nullptr, {}, "The JSON Schema an editor checks the file against (`scene.schema.json`, beside "
                                                 "the bundled scenes); ranryu ignores it."),
                 "none"),
        computed(string("name", nullptr, {}, "The scene's name: `record`'s default folder is `out/NAME`."), "the file's name without `.json`"),
        string("description", "", {}, "One line, shown by `ranryu scenes`."),
        string("model", d.model == Model::sph ? "sph" : "ballistic", {"ballistic", "sph"},
               "What moves the particles: `ballistic` (gravity and bouncing walls only) or `sph` (docs/SPH.md)."),
        vec3("gravity", "m/s²", d.gravity, -1e3, 1e3, "The acceleration of gravity."),

        object("tank", "The axis-aligned box the fluid lives in."),
        vec3("tank.min", "m", d.tank_min, -1e3, 1e3, "The tank's lowest corner."),
        vec3("tank.max", "m", d.tank_max, -1e3, 1e3, "The tank's highest corner; above `tank.min` on every axis."),
        number("tank.restitution", "", d.restitution, 0.0, 1.0, "The ballistic model's walls: the fraction of the normal speed a bounce keeps."),
        boolean("tank.closed", d.tank_closed, "SPH: a lid at `tank.max`'s height, sampled with boundary particles like the walls."),

        object("time", "The frame's length and the ballistic model's substep."),
        number("time.frame_dt", "s", d.frame_dt, 1e-4, 0.1, "Simulated time a frame advances."),
        number("time.substep_dt", "s", d.substep_dt, 1e-6, 0.1,
               "The ballistic model's substep: a frame takes ceil(frame_dt / substep_dt) of them (SPH chooses its own step, `sph.cfl`)."),

        object("particles", "The fluid: its resolution and the blocks of particles it starts as.", true),
        number("particles.spacing", "m", d.spacing, 1e-4, 1.0, "Particle spacing, the resolution (`--spacing` overrides it)."),
        computed(number("particles.radius", "m", d.particle_radius, 1e-5, 1.0, "The radius particles are drawn with."), "spacing / 2"),
        objects("particles.blocks", "Boxes filled with particles on a cubic lattice at min + (i + ½)·spacing; at least one.", true),
        vec3("particles.blocks[].min", "m", Block{}.min, -1e3, 1e3, "The block's lowest corner, inside the tank."),
        required(vec3("particles.blocks[].max", "m", Block{}.max, -1e3, 1e3, "The block's highest corner, inside the tank.")),
        vec3("particles.blocks[].velocity", "m/s", Block{}.velocity, -1e3, 1e3, "The block's initial velocity."),

        objects("obstacles", "Static solids in the tank, sampled with boundary particles (docs/SPH.md (8)): each a sphere "
                             "(`center`, `radius`) or a box (`min`, `max`)."),
        of_kind(vec3("obstacles[].center", "m", Obstacle{}.center, -1e3, 1e3, "A sphere's centre."), "sphere"),
        of_kind(required(number("obstacles[].radius", "m", 0.0f, 1e-4, 1e3, "A sphere's radius.")), "sphere"),
        of_kind(vec3("obstacles[].min", "m", Obstacle{}.min, -1e3, 1e3, "A box's lowest corner."), "box"),
        of_kind(required(vec3("obstacles[].max", "m", Obstacle{}.max, -1e3, 1e3, "A box's highest corner, above `min` on every axis.")), "box"),

        // SPH (docs/SPH.md, docs/DFSPH.md). New keys go at the end of this group.
        object("sph", "The SPH model's settings (`\"model\": \"sph\"`; docs/SPH.md, docs/DFSPH.md)."),
        string("sph.solver", solver_name(h.solver), {"dfsph", "wcsph", "pbf"},
               "The pressure solver: DFSPH (docs/DFSPH.md), WCSPH (docs/SPH.md (3)) or PBF (docs/PBF.md); `--solver` overrides it."),
        number("sph.rest_density", "kg/m³", h.rest_density, 1.0, 1e5, "Rest density ρ0."),
        number("sph.viscosity", "m²/s", h.viscosity, 0.0, 10.0, "Kinematic viscosity ν (docs/SPH.md (5))."),
        number("sph.speed_of_sound", "m/s", h.speed_of_sound, 0.0, 1e4,
               "WCSPH's speed of sound c; 0: 10·sqrt(2 g H), H the fluid's height (docs/SPH.md (3))."),
        number("sph.cfl", "", h.cfl, 0.01, 1.0, "The time step's CFL factor (docs/SPH.md (7), docs/DFSPH.md (D8))."),
        number("sph.force_factor", "", h.force_factor, 0.01, 1.0, "The time step's force factor (docs/SPH.md (7), docs/DFSPH.md (D8))."),
        number("sph.max_time_step", "s", h.max_time_step, 1e-6, 0.1, "The largest step, also at rest (and at most the frame)."),
        number("sph.max_density_error", "", h.max_density_error, 1e-6, 0.1,
               "DFSPH: the density solve's bound η on the density error, a fraction of ρ0 (docs/DFSPH.md (D6))."),
        number("sph.max_divergence_error", "", h.max_divergence_error, 1e-6, 0.1,
               "DFSPH: the divergence solve's bound η_v (docs/DFSPH.md (D6))."),
        integer("sph.min_iterations", "", h.min_iterations, 1, 1000, "DFSPH: the density solve's fewest iterations."),
        integer("sph.max_iterations", "", h.max_iterations, 1, 1000, "DFSPH: the density solve's most iterations."),
        integer("sph.max_divergence_iterations", "", h.max_divergence_iterations, 1, 1000, "DFSPH: the divergence solve's most iterations."),
        integer("sph.shrink_step_above", "", h.shrink_step_above, 0, 1000,
                "DFSPH: a density solve of more iterations than this makes the next steps 0.9 times as long (docs/DFSPH.md (D8)); 0: the iterations never bound the step."),
        integer("sph.grow_step_below", "", h.grow_step_below, 1, 1000,
                "DFSPH: a density solve of fewer iterations than this lets the next steps grow by 1.1 (docs/DFSPH.md (D8))."),
        boolean("sph.divergence_solve", h.divergence_solve, "DFSPH: run the divergence solve (docs/DFSPH.md (D5)); false: the density solve alone."),
        boolean("sph.boundary_rows", h.boundary_rows, "DFSPH: the boundary particles near the fluid are rows of the solves with their own pressure (docs/DFSPH.md (D9)); false: Akinci's boundary term, the fluid particle's pressure once."),
        boolean("sph.eliminate_boundary_rows", h.eliminate_boundary_rows,
                "DFSPH: the density solve's boundary rows take the fluid's pressure extended to them and hand their excess to the fluid, instead of being unknowns of their own (docs/DFSPH.md (D13)); needs sph.boundary_rows. The tank at rest sets it."),
        number("sph.boundary_relaxation", "", h.boundary_relaxation, 0.05, 1.0, "DFSPH: the boundary rows' l1-Jacobi relaxation ω_b (docs/DFSPH.md (D9))."),
        number("sph.warm_start", "", h.warm_start, 0.0, 1.0, "DFSPH: the density solve's warm-start weight w (docs/DFSPH.md (D6))."),
        number("sph.divergence_warm_start", "", h.divergence_warm_start, 0.0, 1.0,
               "DFSPH: the divergence solve's warm-start weight w (docs/DFSPH.md (D6))."),
        number("sph.relaxation", "", h.relaxation, 0.05, 1.0, "DFSPH: the relaxed Jacobi's ω (docs/DFSPH.md (D6))."),
        number("sph.chebyshev", "", h.chebyshev, 0.0, 0.999,
               "DFSPH: ρ of the density solve's Chebyshev acceleration (docs/DFSPH.md (D10)), the spectral radius it assumes of the relaxed Jacobi iteration; 0: plain relaxed Jacobi."),
        boolean("sph.complementarity_error", h.complementarity_error,
                "DFSPH: the density solve's error also counts a particle that carries pressure below ρ0 (|r_i| where κ_i > 0, docs/DFSPH.md (D6)); false: the excess over ρ0 only."),
        boolean("sph.gradient_correction", h.gradient_correction,
                "DFSPH: each pressure acceleration is multiplied by the particle's kernel-gradient correction L_i, so a linear pressure field is differentiated exactly whatever the packing (docs/DFSPH.md (D11)); false: the plain SPH gradient."),
        number("sph.pressure_stabilisation", "", h.pressure_stabilisation, 0.0, 0.5,
               "DFSPH: γ of the density solve's pressure stabilisation (docs/DFSPH.md (D12)): its residual and diagonal blend in a compact Laplacian of κ, which sees the layer-to-layer alternation (D3) cannot; 0: off."),
        number("sph.boundary_viscosity", "m²/s", h.boundary_viscosity, 0.0, 10.0,
               "DFSPH: the walls' viscosity ν_b (docs/DFSPH.md (D7)); 0: free-slip walls."),
        string("sph.neighbour_keys", h.morton ? "morton" : "linear", {"linear", "morton"}, "The neighbour grid's cell order."),
        string("sph.sort", h.sort, {"radix", "bitonic"}, "The neighbour grid's sort."),
        integer("sph.max_substeps", "", h.max_substeps, 1, 10000,
                "The most substeps the CPU issues a frame (a runaway bound; the guard's time-step floor stops a collapse)."),
        boolean("sph.neighbour_masks", h.neighbour_masks,
                "The density pass records which neighbour candidates lie inside h, and the force passes read that (docs/PERFORMANCE.md)."),
        number("sph.density_limit", "", h.density_limit, 1.01, 100.0, "The guard: the largest ρ/ρ0; past it two frames in a row, or past 1 + 2·(limit − 1) once, the run is stopped as unstable (engine/sim/guard.h)."),
        number("sph.speed_limit", "m/s", h.speed_limit, 0.0, 1e5,
               "The guard: the largest speed; past it two frames in a row, or past twice it once, the run is stopped as unstable; 0: 5·(sqrt(2 g H_tank) + the largest initial speed)."),
        number("sph.artificial_viscosity", "", h.artificial_viscosity, 0.0, 1.0,
               "WCSPH: α of Monaghan's artificial viscosity on approaching pairs, ν_α = α·c·Δx / 10 (docs/SPH.md (5a)); 0: none."),
        number("sph.max_particle_density_error", "", h.max_particle_density_error, 0.0, 1.0,
               "DFSPH: the density solve's bound η_p on any one particle's density error, a fraction of ρ0, beside the mean's η (docs/DFSPH.md (D6)); 0: none."),
        number("sph.dfsph_cfl", "", h.dfsph_cfl, 0.0, 1.0,
               "DFSPH: its own Courant number λ of the flow-speed step (docs/DFSPH.md (D8)) in place of `sph.cfl`, which WCSPH's acoustic step keeps; 0: `sph.cfl`."),
        object("sph.pbf", "PBF's settings (`\"solver\": \"pbf\"`, docs/PBF.md): a fixed number of substeps and iterations, so a frame's cost is known."),
        integer("sph.pbf.substeps", "", h.pbf.substeps, 1, 1000, "PBF: substeps a frame at the scene's particles.spacing, each of frame_dt / substeps (docs/PBF.md (P1)); another spacing (--spacing) scales them by the scene's spacing over it, rounded up (docs/PBF.md \"Resolution\")."),
        integer("sph.pbf.iterations", "", h.pbf.iterations, 1, 1000, "PBF: constraint iterations a substep, (P3)–(P6) each."),
        number("sph.pbf.relaxation", "1/dx²", h.pbf.relaxation, 0.0, 100.0,
               "PBF: the constraint's relaxation ε of (P4), in units of 1/Δx² (a full neighbourhood's Σ|∇C|² is about 0.42/Δx²)."),
        number("sph.pbf.s_corr_k", "", h.pbf.s_corr_k, 0.0, 10.0, "PBF: k of the tensile-instability term s_corr (P5); 0: none."),
        integer("sph.pbf.s_corr_n", "", h.pbf.s_corr_n, 1, 16, "PBF: the exponent n of s_corr (P5)."),
        number("sph.pbf.s_corr_dq", "h", h.pbf.s_corr_dq, 0.01, 0.99, "PBF: the distance Δq at which s_corr (P5) is k, in units of h."),
        number("sph.pbf.xsph", "", h.pbf.xsph, 0.0, 1.0, "PBF: the XSPH viscosity's c (P7); 0: none (`sph.viscosity` is not PBF's)."),
        number("sph.pbf.vorticity", "m/s", h.pbf.vorticity, 0.0, 100.0, "PBF: the vorticity confinement's ε (P8); 0: off."),
        number("sph.pbf.warm_start", "", h.pbf.warm_start, 0.0, 1.0,
               "PBF: the weight w of the warm start (P10), the last step's pressure acceleration in the prediction; 0: none."),
        string("sph.why", h.why, {},
               "Why the solver and its step settings are the scene's: the evidence, e.g. the sweep's rows that chose them "
               "(docs/SWEEP.md \"Choosing a scene's settings\"). A comment: the simulation does not read it; `ranryu scenes` and "
               "`profile` print it."),

        object("turbulence", "The wavelet turbulence force (docs/METHOD.md §5, docs/TURBULENCE.md): off unless `amplitude` > 0."),
        number("turbulence.amplitude", "1/m", u.amplitude, 0.0, 1e4, "A: the force per unit mass is A·ê·y (engine/turbulence/force.h); 0: off."),
        number("turbulence.scale", "h", u.scale, 1e-3, 1.0 / 3.0 + 1e-7,
               "The wavelet scale s, in smoothing lengths; at most 1/3, so that 3 s fits in the neighbour grid's cell."),
        {"turbulence.octaves", KeyType::int_pair, "", json::array({u.lmin, u.lmax}), "", -4, 16, {}, false, "",
         "[lmin, lmax]: the noise octaves summed (octave i: wavelengths of about 2..4 · 2^-i m)."},
        number("turbulence.beta", "", u.beta, 0.0, 4.0, "The octaves' falloff 2^(-β(i - lmin)); 1/3: E(k) ∝ k^(-5/3)."),
        integer("turbulence.seed", "", u.seed, 0, 2147483647, "The noise tiles' seed."),
        number("turbulence.coherence_time", "s", u.coherence_time, 1e-3, 1e3,
               "T: each particle's noise coordinates are re-seeded every T, in two phases half a period apart."),
        object("turbulence.subparticles", "Sub-particles where the flow is energetic (docs/METHOD.md §6, docs/SUBPARTICLES.md)."),
        integer("turbulence.subparticles.levels", "", u.subparticles.levels, 0, 3,
                "L_max, the finest level (8^L sub-particles a particle); 0: none. Needs `turbulence.amplitude` > 0."),
        number("turbulence.subparticles.threshold", "m²/s²", u.subparticles.threshold, 1e-9, 1e6,
               "e_th: the wavelet energy ê at which a particle splits to level 1."),
        integer("turbulence.subparticles.budget", "", u.subparticles.budget, 8, 1 << 28,
                "The most sub-particles a frame holds; above it the finest levels are dropped."),

        object("surface", "The liquid's surface (a level set meshed by marching cubes), used by the surface shadings."),
        number("surface.node_spacing", "spacing", f.node_spacing, 0.1, 4.0, "The level set grid's node spacing, in particle spacings."),
        integer("surface.max_dims", "", f.max_dims, 4, 512, "The most grid nodes a side (a larger box coarsens the grid)."),
        integer("surface.max_nodes", "", f.max_nodes, 64, 1 << 27,
                "The most grid nodes in all: the grid coarsens to fit, bounding the surface's cost (docs/SURFACE.md (S9))."),
        boolean("surface.anisotropic", f.anisotropic,
                "Anisotropic kernels (Yu & Turk 2013, docs/SURFACE.md): flat surfaces read flat and thin sheets stay sheets; false: "
                "spherical kernels."),
        integer("surface.max_vertices", "", f.max_vertices, 3, 1 << 26, "The mesh's capacity, 3 a triangle (more are dropped)."),
        vec3("surface.absorption", "1/m", f.absorption, 0.0, 1e3, "Fresnel and water shadings: the water's Beer-Lambert absorption per colour channel (default: pure water's x 12, docs/RENDERING.md (R6))."),

        object("camera", "Where the scene is seen from."),
        vec3("camera.eye", "m", d.camera_eye, -1e4, 1e4, "The camera's position."),
        vec3("camera.target", "m", d.camera_target, -1e4, 1e4, "The point it looks at; not `camera.eye`."),
        number("camera.fov_deg", "°", d.fov_deg, 5.0, 150.0, "The vertical field of view."),

        object("light", "The light."),
        vec3("light.direction", "", d.light_dir, -1.0, 1.0, "Toward the light; normalised on load, not zero."),
        number("light.ambient", "", d.ambient, 0.0, 1.0, "The ambient share of the lighting."),

        object("render", "The default image."),
        integer("render.width", "px", d.width, 16, 8192, "Image width (`--size` overrides it)."),
        integer("render.height", "px", d.height, 16, 8192, "Image height (`--size` overrides it)."),
    };
}

}  // namespace

const char* key_type_name(KeyType t) {
    switch (t) {
        case KeyType::object: return "object";
        case KeyType::objects: return "array of objects";
        case KeyType::number: return "number";
        case KeyType::integer: return "integer";
        case KeyType::boolean: return "boolean";
        case KeyType::string: return "string";
        case KeyType::vec3: return "[x, y, z]";
        case KeyType::int_pair: return "[a, b]";
    }
    return "?";
}

const std::vector<Key>& keys() {
    static const std::vector<Key> table = make_keys();
    return table;
}

const Key* find_key(std::string_view path) {
    for (const Key& k : keys())
        if (k.path == path) return &k;
    return nullptr;
}

const std::vector<Rule>& rules() {
    static const std::vector<Rule> list = {
        {"tank.max, tank.min", "`tank.max` exceeds `tank.min` on every axis."},
        {"particles.blocks", "At least one block; each block's `max` exceeds its `min` on every axis, and the block lies inside the tank."},
        {"particles.spacing", "The blocks hold at least one particle at this spacing (less those inside obstacles) and at most 64 Mi (67108864)."},
        {"obstacles[]", "An item with `radius` or `center` is a sphere and takes only those two; any other is a box, whose `max` exceeds its `min` on every axis."},
        {"sph.min_iterations, sph.max_iterations", "`sph.min_iterations` does not exceed `sph.max_iterations`."},
        {"sph.shrink_step_above, sph.grow_step_below, sph.min_iterations",
         "Where `sph.shrink_step_above` > 0: `sph.grow_step_below` < `sph.shrink_step_above`, and `sph.min_iterations` <= `sph.shrink_step_above`."},
        {"time.frame_dt, time.substep_dt", "At most 1000 substeps a frame: ceil(frame_dt / substep_dt) <= 1000."},
        {"turbulence.octaves", "`[lmin, lmax]` with lmin <= lmax."},
        {"turbulence.amplitude, model", "`turbulence.amplitude` > 0 needs `\"model\": \"sph\"`."},
        {"turbulence.subparticles.levels, turbulence.amplitude", "`turbulence.subparticles.levels` > 0 needs `turbulence.amplitude` > 0."},
        {"camera.eye, camera.target", "`camera.eye` and `camera.target` differ."},
        {"light.direction", "`light.direction` is not zero."},
    };
    return list;
}

namespace {

// A value as the docs show it: numbers as %g to 10 digits (1000, 1e-06, 0.016666668), arrays spaced.
std::string number_text(double x) {
    std::ostringstream s;
    s.precision(10);
    s << x;
    return s.str();
}
std::string value_text(const json& v) {
    if (v.is_number()) return number_text(v.get<double>());
    if (!v.is_array()) return v.dump();
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + value_text(v[i]);
    return s + "]";
}

std::string type_text(const Key& k) {
    if (k.type == KeyType::string && !k.choices.empty()) {
        std::string s = "one of ";
        for (std::size_t i = 0; i < k.choices.size(); ++i) s += (i ? ", `" : "`") + k.choices[i] + "`";
        return s;
    }
    if (k.type == KeyType::int_pair) return "[a, b], integers";
    if (k.type == KeyType::vec3) return "[x, y, z], numbers";
    return key_type_name(k.type);
}

std::string default_text(const Key& k) {
    if (k.required) return "required";
    if (!k.default_note.empty()) return k.default_note;
    if (k.def.is_null()) return "";
    if (k.def.is_string() && k.def.get<std::string>().empty()) return "\"\"";
    return "`" + value_text(k.def) + "`";
}

std::string bounds_text(const Key& k) {
    switch (k.type) {
        case KeyType::number:
        case KeyType::integer:
        case KeyType::vec3:
        case KeyType::int_pair: return "[" + number_text(k.lo) + ", " + number_text(k.hi) + "]";
        default: return "";
    }
}

// The top-level object a key belongs to ("" for the root's own keys).
std::string group_of(const Key& k) {
    const std::size_t dot = k.path.find_first_of(".[");
    if (dot != std::string::npos) return k.path.substr(0, dot);
    return k.type == KeyType::object || k.type == KeyType::objects ? k.path : "";
}

}  // namespace

std::string markdown() {
    std::ostringstream md;
    md << "# Scene files\n\n"
          "<!-- Generated by `ranryu scenes --markdown` from engine/scene/keys.cpp; do not edit. Regenerate with\n"
          "     `cmake --build build/test --target scene-docs` (tests/unit/scene_keys_test.cpp checks it). -->\n\n"
          "A scene is a JSON object (the bundled ones are in `media/scenes/`). Every key is optional unless it\n"
          "says *required*; a key left out takes its default. ranryu checks every key against this table when it\n"
          "loads a scene: an unknown key, a value of the wrong type or outside its bounds, or a broken rule\n"
          "between keys is reported with the file, the key and what is wrong (exit code 2). Numbers must be\n"
          "finite; a `[x, y, z]` has each element within the bounds. `media/scenes/scene.schema.json` (JSON\n"
          "Schema draft 2020-12, generated from the same table) lets an editor check a file as it is written:\n"
          "put `\"$schema\": \"scene.schema.json\"` (a path or URL to it) at the top of the file.\n\n"
          "A path such as `particles.blocks[].min` names the key `min` of every item of the array\n"
          "`particles.blocks`; an error names the item by its index (`particles.blocks[0].min`).\n";
    std::string group = "-";
    for (const Key& k : keys()) {
        const std::string g = group_of(k);
        if (g != group) {
            group = g;
            md << "\n## " << (g.empty() ? "The top level" : "`" + g + "`") << "\n\n";
            if (!g.empty()) md << find_key(g)->meaning << "\n\n";
            md << "| key | type | unit | default | bounds | meaning |\n| --- | --- | --- | --- | --- | --- |\n";
            if (k.path == g) continue;   // its meaning heads the section
        }
        std::string meaning = k.meaning;
        if (!k.variant.empty()) meaning = "(" + k.variant + ") " + meaning;
        md << "| `" << k.path << "` | " << type_text(k) << " | " << k.unit << " | " << default_text(k) << " | " << bounds_text(k)
           << " | " << meaning << " |\n";
    }
    md << "\n## Rules between keys\n\nChecked when the scene loads; JSON Schema cannot say them.\n\n| keys | rule |\n| --- | --- |\n";
    for (const Rule& r : rules()) md << "| " << r.keys << " | " << r.text << " |\n";
    return md.str();
}

namespace {

using ojson = nlohmann::ordered_json;

ojson number_schema(const char* type, double lo, double hi) { return {{"type", type}, {"minimum", lo}, {"maximum", hi}}; }

std::string description(const Key& k) {
    std::string d = k.meaning;
    if (!k.unit.empty()) d += " Unit: " + k.unit + ".";
    if (!k.default_note.empty() && k.default_note != "none") d += " Default: " + k.default_note + ".";
    return d;
}

// The schema of the object whose keys are listed under `prefix` ("" for the root, "sph.",
// "particles.blocks[]."), taking only the keys of `variant` where items come in kinds.
ojson object_schema(const std::string& prefix, const std::string& variant);

ojson key_schema(const Key& k) {
    ojson s;
    switch (k.type) {
        case KeyType::object: s = object_schema(k.path + ".", ""); break;
        case KeyType::objects: {
            std::vector<std::string> variants;
            for (const Key& c : keys())
                if (c.path.starts_with(k.path + "[].") && !c.variant.empty() &&
                    std::find(variants.begin(), variants.end(), c.variant) == variants.end())
                    variants.push_back(c.variant);
            ojson items;
            if (variants.empty()) items = object_schema(k.path + "[].", "");
            else {
                items["oneOf"] = ojson::array();
                for (const std::string& v : variants) {
                    ojson one = object_schema(k.path + "[].", v);
                    one["title"] = v;
                    items["oneOf"].push_back(one);
                }
            }
            s = {{"type", "array"}, {"items", items}};
            if (k.required) s["minItems"] = 1;
            break;
        }
        case KeyType::number: s = number_schema("number", k.lo, k.hi); break;
        case KeyType::integer: s = number_schema("integer", k.lo, k.hi); break;
        case KeyType::boolean: s = {{"type", "boolean"}}; break;
        case KeyType::string:
            s = {{"type", "string"}};
            if (!k.choices.empty()) s["enum"] = k.choices;
            break;
        case KeyType::vec3:
            s = {{"type", "array"}, {"items", number_schema("number", k.lo, k.hi)}, {"minItems", 3}, {"maxItems", 3}};
            break;
        case KeyType::int_pair:
            s = {{"type", "array"}, {"items", number_schema("integer", k.lo, k.hi)}, {"minItems", 2}, {"maxItems", 2}};
            break;
    }
    s["description"] = description(k);
    if (!k.def.is_null()) s["default"] = ojson::parse(k.def.dump());
    return s;
}

ojson object_schema(const std::string& prefix, const std::string& variant) {
    ojson props = ojson::object(), req = ojson::array();
    for (const Key& k : keys()) {
        if (!k.path.starts_with(prefix)) continue;
        const std::string name = k.path.substr(prefix.size());
        if (name.empty() || name.find_first_of(".[") != std::string::npos) continue;   // not a direct child
        if (!variant.empty() && k.variant != variant) continue;
        props[name] = key_schema(k);
        if (k.required) req.push_back(name);
    }
    ojson s = {{"type", "object"}, {"properties", props}, {"additionalProperties", false}};
    if (!req.empty()) s["required"] = req;
    return s;
}

}  // namespace

std::string json_schema() {
    ojson s = {{"$schema", "https://json-schema.org/draft/2020-12/schema"},
               {"$comment", "Generated by `ranryu scenes --schema` from engine/scene/keys.cpp; do not edit (docs/SCENES.md)."},
               {"title", "ranryu scene"},
               {"description", "A ranryu scene file (docs/SCENES.md). The rules between keys are checked when ranryu loads it."}};
    const ojson root = object_schema("", "");
    for (const auto& [name, value] : root.items()) s[name] = value;
    return s.dump(2) + "\n";
}

}  // namespace ranryu::scene
