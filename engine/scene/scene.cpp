#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/embedded.h"
#include "core/error.h"
#include "scene/keys.h"

namespace ranryu::scene {

extern const EmbeddedFile kEmbeddedFiles[];
extern const unsigned kEmbeddedFileCount;

namespace {

using nlohmann::json;

// Largest scene a file may ask for: 64 M particles (about 2 GiB of particle state).
constexpr double kMaxParticles = 64.0 * 1024 * 1024;
// Largest scene file: the bundled ones are about 1 KiB.
constexpr std::uintmax_t kMaxSceneBytes = 1 << 20;

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// A value as an error message shows it: its JSON on one line, cut to 60 characters, so that a huge
// array or a long string still makes a short message (and invalid UTF-8 cannot reach it: parse()
// refuses it).
std::string shown(const json& v) {
    std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
    if (s.size() <= 60) return s;
    std::size_t n = 57;
    while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;   // not inside a UTF-8 sequence
    return s.substr(0, n) + "...";
}

// Reads one JSON object, remembering its dotted path for messages and which keys were used. Each
// key's type, default, bounds and allowed values come from the table (keys.h): `spec_` is the
// object's path there, with "[]" where `path_` has an item's index.
class Reader {
public:
    Reader(const json& j, std::string path, std::string spec, const std::string& origin)
        : j_(j), path_(std::move(path)), spec_(std::move(spec)), origin_(origin) {
        if (!j_.is_object())
            fail(path_.empty() ? "the scene must be a JSON object, not " + shown(j_) : "\"" + path_ + "\" must be an object, not " + shown(j_));
    }

    [[noreturn]] void fail(const std::string& what) const { throw InputError("scene " + origin_ + ": " + what); }

    std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
    bool has(const std::string& k) const { return j_.contains(k); }

    // A number in the table's bounds; absent: the table's default, or `def` where the table's is
    // computed (Key::default_note).
    double number(const std::string& k) { return number_or(k, table_default(k, KeyType::number).get<double>()); }
    double number_or(const std::string& k, double def) {
        const Key& s = spec(k, KeyType::number);
        const json* v = get(k, s);
        if (!v) return def;
        if (!v->is_number()) fail("\"" + key(k) + "\" must be a number, not " + shown(*v));
        return check(key(k), v->get<double>(), s.lo, s.hi);
    }
    double check(const std::string& name, double x, double lo, double hi) const {
        if (!std::isfinite(x) || x < lo || x > hi)
            fail("\"" + name + "\" = " + fmt(x) + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
        return x;
    }
    bool boolean(const std::string& k) {
        const Key& s = spec(k, KeyType::boolean);
        const json* v = get(k, s);
        if (!v) return s.def.get<bool>();
        if (!v->is_boolean()) fail("\"" + key(k) + "\" must be true or false, not " + shown(*v));
        return v->get<bool>();
    }
    int integer(const std::string& k) {
        const Key& s = spec(k, KeyType::integer);
        const json* v = get(k, s);
        if (!v) return s.def.get<int>();
        if (!v->is_number()) fail("\"" + key(k) + "\" must be a number, not " + shown(*v));
        return whole(key(k), check(key(k), v->get<double>(), s.lo, s.hi));
    }
    int whole(const std::string& name, double x) const {
        if (x != std::floor(x)) fail("\"" + name + "\" = " + fmt(x) + " must be a whole number");
        return int(x);
    }
    glm::vec3 vec3(const std::string& k) {
        const Key& s = spec(k, KeyType::vec3);
        const json* v = get(k, s);
        if (!v) return s.required ? glm::vec3(0.0f) : glm::vec3(s.def[0].get<float>(), s.def[1].get<float>(), s.def[2].get<float>());
        const std::vector<double> x = numbers(k, *v, 3);
        glm::vec3 r;
        for (int i = 0; i < 3; ++i) r[i] = float(check(key(k) + "[" + std::to_string(i) + "]", x[std::size_t(i)], s.lo, s.hi));
        return r;
    }
    // A string; one of the table's choices where it lists them. Absent: the table's default, or
    // `def` where the table's is computed.
    std::string string(const std::string& k) { return string_or(k, table_default(k, KeyType::string).get<std::string>()); }
    std::string string_or(const std::string& k, const std::string& def) {
        const Key& s = spec(k, KeyType::string);
        const json* v = get(k, s);
        if (!v) return def;
        if (!v->is_string()) fail("\"" + key(k) + "\" must be a string, not " + shown(*v));
        const std::string x = v->get<std::string>();
        if (!s.choices.empty() && std::find(s.choices.begin(), s.choices.end(), x) == s.choices.end()) {
            std::string list;
            for (const std::string& c : s.choices) list += (list.empty() ? "\"" : ", \"") + c + "\"";
            fail("\"" + key(k) + "\" = " + shown(*v) + " is not one of " + list);
        }
        return x;
    }
    // [a, b] of whole numbers in the table's bounds with a <= b.
    std::pair<int, int> int_pair(const std::string& k) {
        const Key& s = spec(k, KeyType::int_pair);
        const json* v = get(k, s);
        if (!v) return {s.def[0].get<int>(), s.def[1].get<int>()};
        const std::vector<double> x = numbers(k, *v, 2);
        int r[2];
        for (int i = 0; i < 2; ++i) {
            const std::string name = key(k) + "[" + std::to_string(i) + "]";
            r[i] = whole(name, check(name, x[std::size_t(i)], s.lo, s.hi));
        }
        if (r[0] > r[1]) fail("\"" + key(k) + "\" = " + shown(*v) + " must be [lmin, lmax] with lmin <= lmax");
        return {r[0], r[1]};
    }
    Reader object(const std::string& k) {
        const Key& s = spec(k, KeyType::object);
        static const json empty = json::object();
        const json* v = get(k, s);
        return Reader(v ? *v : empty, key(k), s.path, origin_);
    }
    std::vector<Reader> objects(const std::string& k) {
        const Key& s = spec(k, KeyType::objects);
        std::vector<Reader> out;
        const json* v = get(k, s);
        if (!v) return out;
        if (!v->is_array()) fail("\"" + key(k) + "\" must be an array of objects, not " + shown(*v));
        for (std::size_t i = 0; i < v->size(); ++i) out.emplace_back((*v)[i], key(k) + "[" + std::to_string(i) + "]", s.path + "[]", origin_);
        return out;
    }
    // Every key present must have been read: an unknown key is a typo the user needs to hear of.
    void finish() const {
        for (const auto& [k, v] : j_.items())
            if (!used_.count(k)) fail("unknown key \"" + key(k) + "\"");
    }

private:
    // The table's entry for key `k` of this object. Reading a key the table does not list, or as
    // another type, is a mistake in this file, not in the scene.
    const Key& spec(const std::string& k, KeyType type) const {
        const std::string path = spec_.empty() ? k : spec_ + "." + k;
        const Key* s = find_key(path);
        if (!s) throw std::logic_error("scene key \"" + path + "\" is not in the table of scene keys (engine/scene/keys.cpp)");
        if (s->type != type)
            throw std::logic_error("scene key \"" + path + "\" is read as " + key_type_name(type) + " but the table (engine/scene/keys.cpp) says " +
                                   key_type_name(s->type));
        return *s;
    }
    const json& table_default(const std::string& k, KeyType type) const {
        const Key& s = spec(k, type);
        if (s.def.is_null()) throw std::logic_error("scene key \"" + s.path + "\" has no default in the table; read it with a default");
        return s.def;
    }
    // The value of `k`, or nullptr when it is absent (an error if the table says it is required).
    const json* get(const std::string& k, const Key& s) {
        used_.insert(k);
        if (j_.contains(k)) return &j_.at(k);
        // A required object or array is left to the rule that says what it must hold ("particles.blocks"
        // must list at least one block).
        if (s.required && s.type != KeyType::object && s.type != KeyType::objects) fail("\"" + key(k) + "\" must be given" + (s.variant.empty() ? "" : " for a " + s.variant));
        return nullptr;
    }
    // An array of `n` numbers.
    std::vector<double> numbers(const std::string& k, const json& v, std::size_t n) const {
        if (!v.is_array() || v.size() != n || !std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_number(); }))
            fail("\"" + key(k) + "\" must be an array of " + std::to_string(n) + " numbers, not " + shown(v));
        std::vector<double> x;
        for (const json& e : v) x.push_back(e.get<double>());
        return x;
    }

    const json& j_;
    std::string path_, spec_;
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

std::size_t Scene::particle_capacity() const { return std::max(particle_count(), particle_budget); }

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

const char* solver_name(Solver s) {
    switch (s) {
        case Solver::wcsph: return "wcsph";
        case Solver::pbf: return "pbf";
        case Solver::dfsph: break;
    }
    return "dfsph";
}

Solver parse_solver(const std::string& name, const std::string& what) {
    if (name == "dfsph") return Solver::dfsph;
    if (name == "wcsph") return Solver::wcsph;
    if (name == "pbf") return Solver::pbf;
    throw InputError(what + " = \"" + name + "\" is not one of \"dfsph\", \"wcsph\", \"pbf\"");
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

namespace {

// A message from nlohmann's parser with every byte that is not printable ASCII as \xNN: it quotes
// what it last read, which may be anything (invalid UTF-8, control characters).
std::string printable(const std::string& text) {
    std::string out;
    for (const char c : text) {
        const auto b = static_cast<unsigned char>(c);
        if (b >= 0x20 && b < 0x7F) out += c;
        else {
            static const char* hex = "0123456789abcdef";
            out += "\\x";
            out += hex[b >> 4];
            out += hex[b & 15];
        }
    }
    return out;
}

// Scenes nest 5 deep (particles.blocks[i].min[j]); deeper is a mistake, and refused before it can
// cost stack anywhere.
constexpr int kMaxDepth = 32;

}  // namespace

// Every key read here is looked up there for its
// type, default, bounds and allowed values. A new key needs a line in the table and a read here.
Scene parse(const std::string& text, const std::string& origin) {
    json j;
    try {
        j = json::parse(text, [&](int depth, json::parse_event_t, json&) {
            if (depth > kMaxDepth)
                throw InputError("scene " + origin + ": malformed JSON: nested deeper than " + std::to_string(kMaxDepth) + " levels");
            return true;
        });
    } catch (const json::exception& e) {
        // nlohmann's message carries the line and column ("... at line 3, column 5: ..."), or for a
        // number beyond double (1e999) the number.
        std::string what = e.what();
        const auto p = what.find("] ");
        throw InputError("scene " + origin + ": malformed JSON: " + printable(p == std::string::npos ? what : what.substr(p + 2)));
    }
    Scene s;
    s.origin = origin;
    s.source = text;
    Reader r(j, "", "", origin);
    r.string_or("$schema", "");   // for editors (docs/SCENES.md); nothing to ranryu
    s.name = r.string_or("name", "");
    s.description = r.string("description");
    if (s.name.empty()) s.name = std::filesystem::path(origin).stem().string();
    s.model = r.string("model") == "sph" ? Model::sph : Model::ballistic;
    s.gravity = r.vec3("gravity");
    {
        Reader t = r.object("tank");
        s.tank_min = t.vec3("min");
        s.tank_max = t.vec3("max");
        s.restitution = float(t.number("restitution"));
        s.tank_closed = t.boolean("closed");
        for (int a = 0; a < 3; ++a)
            if (!(s.tank_max[a] > s.tank_min[a])) t.fail("\"tank.max\" must exceed \"tank.min\" on every axis");
        t.finish();
    }
    {
        Reader t = r.object("time");
        s.frame_dt = float(t.number("frame_dt"));
        s.substep_dt = float(t.number("substep_dt"));
        if (s.substeps() > 1000) t.fail("\"time.frame_dt\" / \"time.substep_dt\" asks for over 1000 substeps a frame");
        t.finish();
    }
    {
        Reader p = r.object("particles");
        s.spacing = float(p.number("spacing"));
        s.particle_radius = float(p.number_or("radius", 0.5 * s.spacing));
        for (Reader& b : p.objects("blocks")) {
            Block blk;
            blk.min = b.vec3("min");
            blk.max = b.vec3("max");
            blk.velocity = b.vec3("velocity");
            for (int a = 0; a < 3; ++a) {
                if (!(blk.max[a] > blk.min[a])) b.fail("\"" + b.key("max") + "\" must exceed \"" + b.key("min") + "\" on every axis");
                if (blk.min[a] < s.tank_min[a] || blk.max[a] > s.tank_max[a])
                    b.fail("\"" + b.key("min") + "\"..\"" + b.key("max") + "\" must lie inside the tank");
            }
            b.finish();
            s.blocks.push_back(blk);
        }
        if (s.blocks.empty()) p.fail("\"particles.blocks\" must list at least one block");
        p.finish();
    }
    for (Reader& o : r.objects("obstacles")) {
        Obstacle ob;
        if (o.has("radius") || o.has("center")) {
            ob.kind = Obstacle::Kind::sphere;
            ob.center = o.vec3("center");
            ob.radius = float(o.number_or("radius", 0.0));
        } else {
            ob.min = o.vec3("min");
            ob.max = o.vec3("max");
            for (int a = 0; a < 3; ++a)
                if (!(ob.max[a] > ob.min[a])) o.fail("\"" + o.key("max") + "\" must exceed \"" + o.key("min") + "\" on every axis");
        }
        o.finish();
        s.obstacles.push_back(ob);
    }
    {
        // The particle count, with the obstacles known: at least one, at most kMaxParticles.
        double n = 0;
        for (const Block& b : s.blocks) {
            const glm::dvec3 d = glm::dvec3(b.max - b.min) / double(s.spacing);
            n += std::floor(d.x) * std::floor(d.y) * std::floor(d.z);
        }
        if (n > kMaxParticles)
            r.fail("\"particles.spacing\" = " + fmt(s.spacing) + " makes " + fmt(n) + " particles; the limit is " + fmt(kMaxParticles));
        if (s.particle_count() == 0) r.fail("\"particles.spacing\" = " + fmt(s.spacing) + " leaves no particle in any block");
    }
    {
        Reader p = r.object("sph");
        SphSettings& h = s.sph;
        h.solver = parse_solver(p.string("solver"), "scene " + origin + ": \"sph.solver\"");
        h.rest_density = float(p.number("rest_density"));
        h.viscosity = float(p.number("viscosity"));
        h.speed_of_sound = float(p.number("speed_of_sound"));
        h.cfl = float(p.number("cfl"));
        h.force_factor = float(p.number("force_factor"));
        h.max_time_step = float(p.number("max_time_step"));
        h.max_density_error = float(p.number("max_density_error"));
        h.max_divergence_error = float(p.number("max_divergence_error"));
        h.max_particle_density_error = float(p.number("max_particle_density_error"));
        h.min_iterations = p.integer("min_iterations");
        h.max_iterations = p.integer("max_iterations");
        if (h.min_iterations > h.max_iterations) p.fail("\"sph.min_iterations\" must not exceed \"sph.max_iterations\"");
        h.max_divergence_iterations = p.integer("max_divergence_iterations");
        h.shrink_step_above = p.integer("shrink_step_above");
        h.grow_step_below = p.integer("grow_step_below");
        if (h.shrink_step_above > 0 && h.grow_step_below >= h.shrink_step_above)
            p.fail("\"sph.grow_step_below\" (" + fmt(h.grow_step_below) + ") must be below \"sph.shrink_step_above\" (" + fmt(h.shrink_step_above) + ")");
        if (h.shrink_step_above > 0 && h.min_iterations > h.shrink_step_above)
            p.fail("\"sph.min_iterations\" (" + fmt(h.min_iterations) + ") must not exceed \"sph.shrink_step_above\" (" + fmt(h.shrink_step_above) +
                   "): every solve would shrink the step");
        h.divergence_solve = p.boolean("divergence_solve");
        h.boundary_rows = p.boolean("boundary_rows");
        h.eliminate_boundary_rows = p.boolean("eliminate_boundary_rows");
        if (h.eliminate_boundary_rows && !h.boundary_rows)
            p.fail("\"sph.eliminate_boundary_rows\" needs \"sph.boundary_rows\": it changes how the rows of (D9) are solved");
        h.boundary_relaxation = float(p.number("boundary_relaxation"));
        h.warm_start = float(p.number("warm_start"));
        h.divergence_warm_start = float(p.number("divergence_warm_start"));
        h.relaxation = float(p.number("relaxation"));
        h.chebyshev = float(p.number("chebyshev"));
        h.complementarity_error = p.boolean("complementarity_error");
        h.gradient_correction = p.boolean("gradient_correction");
        h.pressure_stabilisation = float(p.number("pressure_stabilisation"));
        h.boundary_viscosity = float(p.number("boundary_viscosity"));
        h.morton = p.string("neighbour_keys") == "morton";
        h.sort = p.string("sort");
        h.max_substeps = p.integer("max_substeps");
        h.neighbour_masks = p.boolean("neighbour_masks");
        h.density_limit = float(p.number("density_limit"));
        h.speed_limit = float(p.number("speed_limit"));
        h.artificial_viscosity = float(p.number("artificial_viscosity"));
        h.dfsph_cfl = float(p.number("dfsph_cfl"));
        if (h.dfsph_cfl > 0.0f && h.dfsph_cfl < 0.01f)
            p.fail("\"sph.dfsph_cfl\" = " + fmt(h.dfsph_cfl) + " must be 0 (DFSPH takes \"sph.cfl\") or in [0.01, 1]");
        {
            Reader b = p.object("pbf");
            PbfSettings& q = h.pbf;
            q.substeps = b.integer("substeps");
            q.iterations = b.integer("iterations");
            q.relaxation = float(b.number("relaxation"));
            q.s_corr_k = float(b.number("s_corr_k"));
            q.s_corr_n = b.integer("s_corr_n");
            q.s_corr_dq = float(b.number("s_corr_dq"));
            q.xsph = float(b.number("xsph"));
            q.vorticity = float(b.number("vorticity"));
            q.warm_start = float(b.number("warm_start"));
            q.reference_substeps = q.substeps;
            q.reference_spacing = s.spacing;
            b.finish();
        }
        h.why = p.string("why");
        p.finish();
    }
    {
        // The turbulence force (docs/METHOD.md §5, engine/turbulence/force.h). scale <= 1/3: the
        // wavelet's truncation radius 3 s must fit in the neighbour grid's cell h (wavelet.h).
        // Octaves up to 16: 2^16 x stays well inside float's exact range for tanks of metres.
        Reader t = r.object("turbulence");
        TurbulenceSettings& u = s.turbulence;
        u.amplitude = float(t.number("amplitude"));
        u.scale = float(t.number("scale"));
        std::tie(u.lmin, u.lmax) = t.int_pair("octaves");
        u.beta = float(t.number("beta"));
        u.seed = std::uint32_t(t.integer("seed"));
        u.coherence_time = float(t.number("coherence_time"));
        {
            // levels <= 3: 512 sub-particles a particle; budget >= 8, one split particle.
            Reader sp = t.object("subparticles");
            SubparticleSettings& q = u.subparticles;
            q.levels = sp.integer("levels");
            q.threshold = float(sp.number("threshold"));
            q.budget = sp.integer("budget");
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
        u.node_spacing = float(f.number("node_spacing"));
        u.max_dims = f.integer("max_dims");
        u.max_nodes = f.integer("max_nodes");
        u.anisotropic = f.boolean("anisotropic");
        u.max_vertices = f.integer("max_vertices");
        u.absorption = f.vec3("absorption");
        f.finish();
    }
    {
        Reader c = r.object("camera");
        s.camera_eye = c.vec3("eye");
        s.camera_target = c.vec3("target");
        s.fov_deg = float(c.number("fov_deg"));
        if (glm::length(s.camera_eye - s.camera_target) < 1e-4f) c.fail("\"camera.eye\" and \"camera.target\" coincide");
        c.finish();
    }
    {
        Reader l = r.object("light");
        s.light_dir = l.vec3("direction");
        s.ambient = float(l.number("ambient"));
        if (glm::length(s.light_dir) < 1e-3f) l.fail("\"light.direction\" must not be zero");
        s.light_dir = glm::normalize(s.light_dir);
        l.finish();
    }
    {
        Reader v = r.object("render");
        s.width = v.integer("width");
        s.height = v.integer("height");
        v.finish();
    }
    r.finish();
    return s;
}

Scene load(const std::string& name_or_path) {
    std::error_code exists_ec;   // a name too long for a path is not a path
    const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                                 name_or_path.ends_with(".json") || std::filesystem::exists(name_or_path, exists_ec);
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
    // A folder, a device or a pipe where the file belongs would read as nothing, or never end.
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(name_or_path, ec);
    if (fs::is_directory(st)) throw InputError("scene " + name_or_path + ": is a folder, not a scene file");
    if (fs::exists(st) && !fs::is_regular_file(st)) throw InputError("scene " + name_or_path + ": is not a regular file");
    if (fs::is_regular_file(st)) {
        const std::uintmax_t size = fs::file_size(name_or_path, ec);
        if (!ec && size > kMaxSceneBytes)
            throw InputError("scene " + name_or_path + ": the file is " + std::to_string(size) + " bytes; a scene file is at most " +
                             std::to_string(kMaxSceneBytes));
    }
    std::ifstream in(name_or_path, std::ios::binary);
    if (!in) throw InputError("scene " + name_or_path + ": cannot read the file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse(ss.str(), name_or_path);
}

Scene with_spacing(Scene s, float dx, const std::string& what) {
    if (!(dx >= 1e-4f && dx <= 1.0f)) throw InputError(what + ": spacing " + fmt(dx) + " m is out of range [0.0001, 1]");
    // PBF's fixed step keeps its Courant number: sph.pbf.substeps are the scene's at its own spacing,
    // and the step may move the flow no more spacings at another (docs/PBF.md "Resolution").
    const PbfSettings& q = s.sph.pbf;
    const bool referenced = q.reference_substeps > 0 && q.reference_spacing > 0.0f;
    const double from = referenced ? double(q.reference_substeps) * double(q.reference_spacing) : double(q.substeps) * double(s.spacing);
    // Rounded up, but a ratio within float rounding of a whole number is that number (8 at 0.0125 m
    // are 5 at 0.02 m, not 6, although in doubles 8 · 0.0125f / 0.02f is 5.0000002).
    const double ratio = from / double(dx), substeps = std::ceil(ratio * (1.0 - 1e-6));
    s.sph.pbf.substeps = int(std::clamp(substeps, 1.0, 1000.0));
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
        out.push_back({name, s.description, s.sph.why});
    }
    return out;
}

}  // namespace ranryu::scene
