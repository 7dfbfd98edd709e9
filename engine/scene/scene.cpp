#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/embedded.h"
#include "core/error.h"

namespace ranryu::scene {

extern const EmbeddedFile kEmbeddedFiles[];
extern const unsigned kEmbeddedFileCount;

namespace {

using nlohmann::json;

// Largest scene a file may ask for: 64 M particles (about 2 GiB of particle state).
constexpr double kMaxParticles = 64.0 * 1024 * 1024;

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// Reads one JSON object, remembering its dotted path for messages and which keys were used.
class Reader {
public:
    Reader(const json& j, std::string path, const std::string& origin) : j_(j), path_(std::move(path)), origin_(origin) {
        if (!j_.is_object()) fail(path_.empty() ? "the scene must be a JSON object" : "\"" + path_ + "\" must be an object");
    }

    [[noreturn]] void fail(const std::string& what) const { throw InputError("scene " + origin_ + ": " + what); }

    std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
    bool has(const std::string& k) const { return j_.contains(k); }

    double number(const std::string& k, double def, double lo, double hi) {
        used_.insert(k);
        if (!j_.contains(k)) return def;
        const json& v = j_.at(k);
        if (!v.is_number()) fail("\"" + key(k) + "\" must be a number, not " + v.dump());
        return check(key(k), v.get<double>(), lo, hi);
    }
    double check(const std::string& name, double x, double lo, double hi) const {
        if (!std::isfinite(x) || x < lo || x > hi)
            fail("\"" + name + "\" = " + fmt(x) + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
        return x;
    }
    bool boolean(const std::string& k, bool def) {
        used_.insert(k);
        if (!j_.contains(k)) return def;
        const json& v = j_.at(k);
        if (!v.is_boolean()) fail("\"" + key(k) + "\" must be true or false, not " + v.dump());
        return v.get<bool>();
    }
    int integer(const std::string& k, int def, int lo, int hi) {
        const double x = number(k, def, lo, hi);
        if (x != std::floor(x)) fail("\"" + key(k) + "\" = " + fmt(x) + " must be a whole number");
        return int(x);
    }
    glm::vec3 vec3(const std::string& k, glm::vec3 def, double lo, double hi) {
        used_.insert(k);
        if (!j_.contains(k)) return def;
        const json& v = j_.at(k);
        if (!v.is_array() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_number(); }))
            fail("\"" + key(k) + "\" must be an array of 3 numbers, not " + v.dump());
        glm::vec3 r;
        for (int i = 0; i < 3; ++i) r[i] = float(check(key(k) + "[" + std::to_string(i) + "]", v[std::size_t(i)].get<double>(), lo, hi));
        return r;
    }
    std::string string(const std::string& k, const std::string& def) {
        used_.insert(k);
        if (!j_.contains(k)) return def;
        if (!j_.at(k).is_string()) fail("\"" + key(k) + "\" must be a string");
        return j_.at(k).get<std::string>();
    }
    // [a, b] of whole numbers in [lo, hi] with a <= b.
    std::pair<int, int> int_pair(const std::string& k, std::pair<int, int> def, int lo, int hi) {
        used_.insert(k);
        if (!j_.contains(k)) return def;
        const json& v = j_.at(k);
        if (!v.is_array() || v.size() != 2 || !std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_number(); }))
            fail("\"" + key(k) + "\" must be an array of 2 numbers, not " + v.dump());
        int r[2];
        for (int i = 0; i < 2; ++i) {
            const std::string name = key(k) + "[" + std::to_string(i) + "]";
            const double x = check(name, v[std::size_t(i)].get<double>(), lo, hi);
            if (x != std::floor(x)) fail("\"" + name + "\" = " + fmt(x) + " must be a whole number");
            r[i] = int(x);
        }
        if (r[0] > r[1]) fail("\"" + key(k) + "\" = " + v.dump() + " must be [lmin, lmax] with lmin <= lmax");
        return {r[0], r[1]};
    }
    Reader object(const std::string& k) {
        used_.insert(k);
        static const json empty = json::object();
        return Reader(j_.contains(k) ? j_.at(k) : empty, key(k), origin_);
    }
    std::vector<Reader> objects(const std::string& k) {
        used_.insert(k);
        std::vector<Reader> out;
        if (!j_.contains(k)) return out;
        if (!j_.at(k).is_array()) fail("\"" + key(k) + "\" must be an array of objects");
        for (std::size_t i = 0; i < j_.at(k).size(); ++i)
            out.emplace_back(j_.at(k)[i], key(k) + "[" + std::to_string(i) + "]", origin_);
        return out;
    }
    // Every key present must have been read: an unknown key is a typo the user needs to hear of.
    void finish() const {
        for (const auto& [k, v] : j_.items())
            if (!used_.count(k)) fail("unknown key \"" + key(k) + "\"");
    }

private:
    const json& j_;
    std::string path_;
    const std::string& origin_;
    std::set<std::string> used_;
};

int lattice_count(float lo, float hi, float spacing) { return std::max(0, int(std::floor((hi - lo) / spacing + 1e-4f))); }

}  // namespace

bool Obstacle::contains(glm::vec3 p, float margin) const {
    if (kind == Kind::sphere) return glm::length(p - center) < radius + margin;
    return glm::all(glm::greaterThan(p, min - margin)) && glm::all(glm::lessThan(p, max + margin));
}

float Scene::fluid_height() const {
    float top = tank_min.y;
    for (const Block& b : blocks) top = std::max(top, b.max.y);
    return top - tank_min.y;
}

float Scene::speed_estimate() const {
    float v0 = 0.0f;
    for (const Block& b : blocks) v0 = std::max(v0, glm::length(b.velocity));
    return std::sqrt(2.0f * glm::length(gravity) * (tank_max.y - tank_min.y)) + v0;
}

float Scene::sound_speed() const {
    if (sph.solver != Solver::wcsph) return 0.0f;
    if (sph.speed_of_sound > 0.0f) return sph.speed_of_sound;
    float v0 = 0.0f;
    for (const Block& b : blocks) v0 = std::max(v0, glm::length(b.velocity));
    return 10.0f * std::max(std::sqrt(2.0f * glm::length(gravity) * fluid_height()) + v0, 0.1f);
}

int Scene::substeps() const { return std::max(1, int(std::ceil(frame_dt / substep_dt - 1e-4f))); }

namespace {
// Calls f(position, block) for every lattice site of every block that no obstacle covers.
template <class F>
void for_each_site(const Scene& s, F&& f) {
    for (const Block& b : s.blocks) {
        const int nx = lattice_count(b.min.x, b.max.x, s.spacing), ny = lattice_count(b.min.y, b.max.y, s.spacing),
                  nz = lattice_count(b.min.z, b.max.z, s.spacing);
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) {
                    const glm::vec3 p = b.min + (glm::vec3(float(i), float(j), float(k)) + 0.5f) * s.spacing;
                    if (std::none_of(s.obstacles.begin(), s.obstacles.end(),
                                     [&](const Obstacle& o) { return o.contains(p, 0.5f * s.spacing); }))
                        f(p, b);
                }
    }
}
}  // namespace

std::size_t Scene::particle_count() const {
    std::size_t n = 0;
    if (obstacles.empty()) {   // every site counts: no need to visit them (the memory check counts 64M)
        for (const Block& b : blocks)
            n += std::size_t(lattice_count(b.min.x, b.max.x, spacing)) * std::size_t(lattice_count(b.min.y, b.max.y, spacing)) *
                 std::size_t(lattice_count(b.min.z, b.max.z, spacing));
        return n;
    }
    for_each_site(*this, [&](glm::vec3, const Block&) { ++n; });
    return n;
}

std::vector<glm::vec4> Scene::initial_positions() const {
    std::vector<glm::vec4> p;
    for_each_site(*this, [&](glm::vec3 x, const Block&) { p.emplace_back(x, 0.0f); });
    return p;
}

std::vector<glm::vec4> Scene::initial_velocities() const {
    std::vector<glm::vec4> v;
    for_each_site(*this, [&](glm::vec3, const Block& b) { v.emplace_back(b.velocity, 0.0f); });
    return v;
}

const char* solver_name(Solver s) { return s == Solver::wcsph ? "wcsph" : "dfsph"; }

Solver parse_solver(const std::string& name, const std::string& what) {
    if (name == "dfsph") return Solver::dfsph;
    if (name == "wcsph") return Solver::wcsph;
    throw InputError(what + " = \"" + name + "\" is not one of \"dfsph\", \"wcsph\"");
}

std::vector<float> Scene::initial_pressures() const {
    std::vector<float> p;
    const float g = glm::length(gravity);
    for_each_site(*this, [&](glm::vec3 x, const Block& b) {
        const bool resting = b.min.y <= tank_min.y + 1e-6f && glm::length(b.velocity) == 0.0f;
        p.push_back(resting ? sph.rest_density * g * std::max(b.max.y - x.y, 0.0f) : 0.0f);
    });
    return p;
}

Scene parse(const std::string& text, const std::string& origin) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        // nlohmann's message carries the line and column ("... at line 3, column 5: ...").
        std::string what = e.what();
        const auto p = what.find("] ");
        throw InputError("scene " + origin + ": malformed JSON: " + (p == std::string::npos ? what : what.substr(p + 2)));
    }
    Scene s;
    s.origin = origin;
    Reader r(j, "", origin);
    s.name = r.string("name", "");
    s.description = r.string("description", "");
    if (s.name.empty()) s.name = std::filesystem::path(origin).stem().string();

    {
        Reader t = r.object("tank");
        s.tank_min = t.vec3("min", s.tank_min, -1e3, 1e3);
        s.tank_max = t.vec3("max", s.tank_max, -1e3, 1e3);
        s.restitution = float(t.number("restitution", s.restitution, 0.0, 1.0));
        s.tank_closed = t.boolean("closed", s.tank_closed);
        for (int a = 0; a < 3; ++a)
            if (!(s.tank_max[a] > s.tank_min[a])) t.fail("\"tank.max\" must exceed \"tank.min\" on every axis");
        t.finish();
    }
    s.gravity = r.vec3("gravity", s.gravity, -1e3, 1e3);
    {
        const std::string model = r.string("model", "ballistic");
        if (model == "sph") s.model = Model::sph;
        else if (model != "ballistic") r.fail("\"model\" = \"" + model + "\" is not one of \"ballistic\", \"sph\"");
    }
    {
        Reader p = r.object("sph");
        SphSettings& h = s.sph;
        h.solver = parse_solver(p.string("solver", solver_name(h.solver)), "scene " + origin + ": \"sph.solver\"");
        h.rest_density = float(p.number("rest_density", h.rest_density, 1.0, 1e5));
        h.viscosity = float(p.number("viscosity", h.viscosity, 0.0, 10.0));
        h.speed_of_sound = float(p.number("speed_of_sound", h.speed_of_sound, 0.0, 1e4));
        h.cfl = float(p.number("cfl", h.cfl, 0.01, 1.0));
        h.force_factor = float(p.number("force_factor", h.force_factor, 0.01, 1.0));
        h.max_time_step = float(p.number("max_time_step", h.max_time_step, 1e-6, 0.1));
        h.max_density_error = float(p.number("max_density_error", h.max_density_error, 1e-6, 0.1));
        h.max_divergence_error = float(p.number("max_divergence_error", h.max_divergence_error, 1e-6, 0.1));
        h.min_iterations = p.integer("min_iterations", h.min_iterations, 1, 1000);
        h.max_iterations = p.integer("max_iterations", h.max_iterations, 1, 1000);
        if (h.min_iterations > h.max_iterations) p.fail("\"sph.min_iterations\" must not exceed \"sph.max_iterations\"");
        h.max_divergence_iterations = p.integer("max_divergence_iterations", h.max_divergence_iterations, 1, 1000);
        h.divergence_solve = p.boolean("divergence_solve", h.divergence_solve);
        h.warm_start = float(p.number("warm_start", h.warm_start, 0.0, 1.0));
        h.divergence_warm_start = float(p.number("divergence_warm_start", h.divergence_warm_start, 0.0, 1.0));
        h.relaxation = float(p.number("relaxation", h.relaxation, 0.05, 1.0));
        h.boundary_viscosity = float(p.number("boundary_viscosity", h.boundary_viscosity, 0.0, 10.0));
        const std::string keys = p.string("neighbour_keys", "linear");
        if (keys != "linear" && keys != "morton") p.fail("\"sph.neighbour_keys\" = \"" + keys + "\" is not one of \"linear\", \"morton\"");
        h.morton = keys == "morton";
        h.sort = p.string("sort", h.sort);
        if (h.sort != "radix" && h.sort != "bitonic") p.fail("\"sph.sort\" = \"" + h.sort + "\" is not one of \"radix\", \"bitonic\"");
        h.max_substeps = p.integer("max_substeps", h.max_substeps, 1, 10000);
        h.neighbour_masks = p.boolean("neighbour_masks", h.neighbour_masks);
        h.density_limit = float(p.number("density_limit", h.density_limit, 1.01, 100.0));
        h.speed_limit = float(p.number("speed_limit", h.speed_limit, 0.0, 1e5));
        p.finish();
    }
    {
        // The turbulence force (docs/METHOD.md §5, engine/turbulence/force.h). scale <= 1/3: the
        // wavelet's truncation radius 3 s must fit in the neighbour grid's cell h (wavelet.h).
        // Octaves up to 16: 2^16 x stays well inside float's exact range for tanks of metres.
        Reader t = r.object("turbulence");
        TurbulenceSettings& u = s.turbulence;
        u.amplitude = float(t.number("amplitude", u.amplitude, 0.0, 1e4));
        u.scale = float(t.number("scale", u.scale, 1e-3, 1.0 / 3.0 + 1e-7));
        const auto oct = t.int_pair("octaves", {u.lmin, u.lmax}, -4, 16);
        u.lmin = oct.first;
        u.lmax = oct.second;
        u.beta = float(t.number("beta", u.beta, 0.0, 4.0));
        u.seed = std::uint32_t(t.integer("seed", int(u.seed), 0, 2147483647));
        u.coherence_time = float(t.number("coherence_time", u.coherence_time, 1e-3, 1e3));
        {
            // levels <= 3: 512 sub-particles a particle; budget >= 8, one split particle.
            Reader sp = t.object("subparticles");
            SubparticleSettings& q = u.subparticles;
            q.levels = sp.integer("levels", q.levels, 0, 3);
            q.threshold = float(sp.number("threshold", q.threshold, 1e-9, 1e6));
            q.budget = sp.integer("budget", q.budget, 8, 1 << 28);
            sp.finish();
            if (q.enabled() && !u.enabled())
                t.fail("\"turbulence.subparticles.levels\" > 0 needs \"turbulence.amplitude\" > 0 (the wavelet energy it splits by)");
        }
        if (u.enabled() && s.model != Model::sph) t.fail("\"turbulence.amplitude\" > 0 needs \"model\": \"sph\"");
        t.finish();
    }
    {
        // max_dims: 512^3 nodes keep every cell index and buffer offset in 32 bits (134M cells);
        // max_vertices: 2^26 vertices are 2 GiB of mesh.
        Reader f = r.object("surface");
        SurfaceSettings& u = s.surface;
        u.node_spacing = float(f.number("node_spacing", u.node_spacing, 0.1, 4.0));
        u.max_dims = f.integer("max_dims", u.max_dims, 4, 512);
        u.max_vertices = f.integer("max_vertices", u.max_vertices, 3, 1 << 26);
        u.absorption = f.vec3("absorption", u.absorption, 0.0, 1e3);
        f.finish();
    }
    {
        Reader t = r.object("time");
        s.frame_dt = float(t.number("frame_dt", s.frame_dt, 1e-4, 0.1));
        s.substep_dt = float(t.number("substep_dt", s.substep_dt, 1e-6, 0.1));
        if (s.substeps() > 1000) t.fail("\"time.frame_dt\" / \"time.substep_dt\" asks for over 1000 substeps a frame");
        t.finish();
    }
    for (Reader& o : r.objects("obstacles")) {
        Obstacle ob;
        if (o.has("radius") || o.has("center")) {
            ob.kind = Obstacle::Kind::sphere;
            ob.center = o.vec3("center", ob.center, -1e3, 1e3);
            ob.radius = float(o.number("radius", 0.0, 1e-4, 1e3));
            if (ob.radius <= 0.0f) o.fail("\"" + o.key("radius") + "\" must be given for a sphere");
        } else {
            ob.min = o.vec3("min", ob.min, -1e3, 1e3);
            ob.max = o.vec3("max", ob.max, -1e3, 1e3);
            for (int a = 0; a < 3; ++a)
                if (!(ob.max[a] > ob.min[a])) o.fail("\"" + o.key("max") + "\" must exceed \"" + o.key("min") + "\" on every axis");
        }
        o.finish();
        s.obstacles.push_back(ob);
    }
    {
        Reader p = r.object("particles");
        s.spacing = float(p.number("spacing", s.spacing, 1e-4, 1.0));
        s.particle_radius = float(p.number("radius", 0.5 * s.spacing, 1e-5, 1.0));
        for (Reader& b : p.objects("blocks")) {
            Block blk;
            blk.min = b.vec3("min", blk.min, -1e3, 1e3);
            blk.max = b.vec3("max", blk.max, -1e3, 1e3);
            blk.velocity = b.vec3("velocity", blk.velocity, -1e3, 1e3);
            for (int a = 0; a < 3; ++a) {
                if (!(blk.max[a] > blk.min[a])) b.fail("\"" + b.key("max") + "\" must exceed \"" + b.key("min") + "\" on every axis");
                if (blk.min[a] < s.tank_min[a] || blk.max[a] > s.tank_max[a])
                    b.fail("\"" + b.key("min") + "\"..\"" + b.key("max") + "\" must lie inside the tank");
            }
            b.finish();
            s.blocks.push_back(blk);
        }
        if (s.blocks.empty()) p.fail("\"particles.blocks\" must list at least one block");
        double n = 0;
        for (const Block& b : s.blocks) {
            const glm::dvec3 d = glm::dvec3(b.max - b.min) / double(s.spacing);
            n += std::floor(d.x) * std::floor(d.y) * std::floor(d.z);
        }
        if (n > kMaxParticles) p.fail("\"particles.spacing\" = " + fmt(s.spacing) + " makes " + fmt(n) + " particles; the limit is " + fmt(kMaxParticles));
        if (s.particle_count() == 0) p.fail("\"particles.spacing\" = " + fmt(s.spacing) + " leaves no particle in any block");
        p.finish();
    }
    {
        Reader c = r.object("camera");
        s.camera_eye = c.vec3("eye", s.camera_eye, -1e4, 1e4);
        s.camera_target = c.vec3("target", s.camera_target, -1e4, 1e4);
        s.fov_deg = float(c.number("fov_deg", s.fov_deg, 5.0, 150.0));
        if (glm::length(s.camera_eye - s.camera_target) < 1e-4f) c.fail("\"camera.eye\" and \"camera.target\" coincide");
        c.finish();
    }
    {
        Reader l = r.object("light");
        s.light_dir = l.vec3("direction", s.light_dir, -1.0, 1.0);
        s.ambient = float(l.number("ambient", s.ambient, 0.0, 1.0));
        if (glm::length(s.light_dir) < 1e-3f) l.fail("\"light.direction\" must not be zero");
        s.light_dir = glm::normalize(s.light_dir);
        l.finish();
    }
    {
        Reader v = r.object("render");
        s.width = v.integer("width", s.width, 16, 8192);
        s.height = v.integer("height", s.height, 16, 8192);
        v.finish();
    }
    r.finish();
    return s;
}

Scene load(const std::string& name_or_path) {
    const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                                 name_or_path.ends_with(".json") || std::filesystem::exists(name_or_path);
    if (!looks_like_path) {
        const std::string key = "scenes/" + name_or_path + ".json";
        for (unsigned i = 0; i < kEmbeddedFileCount; ++i)
            if (kEmbeddedFiles[i].path == key) {
                Scene s = parse(std::string(kEmbeddedFiles[i].text), name_or_path + " (bundled)");
                s.origin = "bundled";
                return s;
            }
        std::string names;
        for (const BundledScene& b : bundled()) names += (names.empty() ? "" : ", ") + b.name;
        throw InputError("scene \"" + name_or_path + "\": no bundled scene of that name (bundled: " + names +
                         "; or give a path to a .json file)");
    }
    std::ifstream in(name_or_path, std::ios::binary);
    if (!in) throw InputError("scene " + name_or_path + ": cannot read the file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse(ss.str(), name_or_path);
}

Scene with_spacing(Scene s, float dx, const std::string& what) {
    if (!(dx >= 1e-4f && dx <= 1.0f)) throw InputError(what + ": spacing " + fmt(dx) + " m is out of range [0.0001, 1]");
    s.spacing = dx;
    s.particle_radius = 0.5f * dx;
    const std::size_t n = s.particle_count();
    if (n == 0) throw InputError(what + ": spacing " + fmt(dx) + " m leaves no particle in scene " + s.name);
    if (double(n) > kMaxParticles)
        throw InputError(what + ": spacing " + fmt(dx) + " m makes " + std::to_string(n) + " particles; the limit is " + fmt(kMaxParticles));
    return s;
}

std::string bundled_file(const std::string& path) {
    for (unsigned i = 0; i < kEmbeddedFileCount; ++i)
        if (kEmbeddedFiles[i].path == path) return std::string(kEmbeddedFiles[i].text);
    throw Error("no bundled file " + path);
}

std::vector<BundledScene> bundled() {
    std::vector<BundledScene> out;
    for (unsigned i = 0; i < kEmbeddedFileCount; ++i) {
        const std::string path(kEmbeddedFiles[i].path);
        if (!path.starts_with("scenes/") || !path.ends_with(".json")) continue;
        const std::string name = path.substr(7, path.size() - 12);
        const Scene s = parse(std::string(kEmbeddedFiles[i].text), name + " (bundled)");
        out.push_back({name, s.description});
    }
    return out;
}

}  // namespace ranryu::scene
