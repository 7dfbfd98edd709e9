// The table of scene keys (engine/scene/keys.cpp) against the parser and the generated files: the
// committed docs/SCENES.md and media/scenes/scene.schema.json are what the table gives; the parser
// reads every key of the table and refuses its values outside the table's bounds, naming the key; and
// every bundled scene satisfies the schema while the bad test scenes do not.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/keys.h"
#include "scene/scene.h"

using namespace ranryu::scene;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = RANRYU_SOURCE_DIR;

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) return "";
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The first line where `a` and `b` differ, for the failure message.
std::string first_difference(const std::string& a, const std::string& b) {
    std::istringstream x(a), y(b);
    std::string lx, ly;
    for (int line = 1;; ++line) {
        const bool more_x = bool(std::getline(x, lx)), more_y = bool(std::getline(y, ly));
        if (!more_x && !more_y) return "none";
        if (!more_x || !more_y || lx != ly)
            return "line " + std::to_string(line) + ":\n  committed: " + (more_x ? lx : "(end)") + "\n  generated: " + (more_y ? ly : "(end)");
    }
}

// A valid scene, SPH so that every key may be set, with one sphere and one box obstacle.
json base_scene() {
    return json::parse(R"({
      "model": "sph",
      "tank": {"min": [0, 0, 0], "max": [1, 1, 1]},
      "particles": {"spacing": 0.1, "blocks": [{"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}]},
      "obstacles": [{"center": [0.8, 0.8, 0.8], "radius": 0.05}, {"min": [0.7, 0.1, 0.7], "max": [0.9, 0.3, 0.9]}]
    })");
}

// The JSON pointer of a table path in base_scene(): array items are the first of their kind.
json::json_pointer pointer(const Key& k) {
    std::string p;
    std::string path = k.path;
    for (std::size_t at = 0; at <= path.size();) {
        const std::size_t dot = std::min(path.find('.', at), path.size());
        std::string part = path.substr(at, dot - at);
        const bool item = part.ends_with("[]");
        if (item) part.resize(part.size() - 2);
        p += "/" + part;
        if (item) p += k.variant == "box" ? "/1" : "/0";
        at = dot + 1;
    }
    return json::json_pointer(p);
}

// The message of the InputError that parsing `scene` raises ("" if none).
std::string error_of(const json& scene) {
    try {
        parse(scene.dump(), "keys.json");
    } catch (const ranryu::InputError& e) {
        return e.what();
    }
    return "";
}

// The path as an error names it: the first item of an array of its kind.
std::string named(const Key& k) {
    std::string p = k.path;
    for (std::size_t at; (at = p.find("[]")) != std::string::npos;) p.replace(at, 2, k.variant == "box" ? "[1]" : "[0]");
    return p;
}

// ---- a JSON Schema check of what scene.schema.json uses: type, enum, minimum, maximum, items,
// minItems, maxItems, properties, required, additionalProperties: false, oneOf ----
bool satisfies(const json& v, const json& s, std::string& why, const std::string& at = "") {
    if (s.contains("oneOf")) {
        int n = 0;
        for (const json& one : s["oneOf"]) {
            std::string ignored;
            n += satisfies(v, one, ignored, at);
        }
        if (n != 1) return why = at + ": matches " + std::to_string(n) + " of oneOf", false;
        return true;
    }
    const std::string type = s.value("type", "");
    if (type == "object") {
        if (!v.is_object()) return why = at + ": not an object", false;
        for (const json& r : s.value("required", json::array()))
            if (!v.contains(r.get<std::string>())) return why = at + ": lacks " + r.get<std::string>(), false;
        for (const auto& [name, value] : v.items()) {
            if (!s["properties"].contains(name)) return why = at + ": unknown " + name, false;
            if (!satisfies(value, s["properties"][name], why, at + "/" + name)) return false;
        }
        return true;
    }
    if (type == "array") {
        if (!v.is_array()) return why = at + ": not an array", false;
        if (v.size() < s.value("minItems", 0u) || v.size() > s.value("maxItems", 1000000u)) return why = at + ": length", false;
        for (std::size_t i = 0; i < v.size(); ++i)
            if (!satisfies(v[i], s["items"], why, at + "/" + std::to_string(i))) return false;
        return true;
    }
    if (type == "number" || type == "integer") {
        if (!v.is_number()) return why = at + ": not a number", false;
        const double x = v.get<double>();
        if (type == "integer" && x != std::floor(x)) return why = at + ": not whole", false;
        if (x < s["minimum"].get<double>() || x > s["maximum"].get<double>()) return why = at + ": out of bounds", false;
        return true;
    }
    if (type == "boolean") return v.is_boolean() || (why = at + ": not a boolean", false);
    if (type == "string") {
        if (!v.is_string()) return why = at + ": not a string", false;
        if (s.contains("enum") && std::find(s["enum"].begin(), s["enum"].end(), v) == s["enum"].end())
            return why = at + ": not in enum", false;
        return true;
    }
    return why = at + ": unknown schema type " + type, false;
}

}  // namespace

TEST_CASE("scene keys: docs/SCENES.md and media/scenes/scene.schema.json are what the table gives", "[scene-keys]") {
    const std::pair<fs::path, std::string> files[] = {{"docs/SCENES.md", markdown()}, {"media/scenes/scene.schema.json", json_schema()}};
    for (const auto& [file, generated] : files) {
        INFO(file.string() << " differs from what engine/scene/keys.cpp gives; regenerate it with\n"
                           << "  cmake --build build/test --target scene-docs\n"
                           << "(or `ranryu scenes --markdown > docs/SCENES.md`, `ranryu scenes --schema > "
                              "media/scenes/scene.schema.json`) and commit it. First difference at "
                           << first_difference(read(kSource / file), generated));
        CHECK(read(kSource / file) == generated);
    }
}

TEST_CASE("scene keys: the parser reads every key of the table and refuses values outside its bounds, naming the key",
          "[scene-keys]") {
    REQUIRE(error_of(base_scene()) == "");
    for (const Key& k : keys()) {
        if (k.type == KeyType::object || k.type == KeyType::objects) continue;
        INFO(k.path);
        const json::json_pointer at = pointer(k);
        const std::string name = named(k);
        // Set to its default (or, where the default is computed or the key required, a valid value):
        // accepted, so the parser reads it.
        json scene = base_scene();
        if (!k.def.is_null()) scene[at] = k.def;
        else if (k.type == KeyType::string) scene[at] = "x";
        else if (!scene.contains(at)) scene[at] = k.type == KeyType::vec3 ? json::array({0.01, 0.01, 0.01}) : json(0.01);
        CHECK(error_of(scene) == "");
        // The wrong type.
        scene[at] = json::object({{"a", 1}});
        CHECK_THAT(error_of(scene), Catch::Contains("keys.json") && Catch::Contains("\"" + name + "\" must be"));
        // Outside the bounds, on either side.
        if (k.type == KeyType::number || k.type == KeyType::integer || k.type == KeyType::vec3 || k.type == KeyType::int_pair) {
            for (const double x : {k.hi + std::max(1.0, std::abs(k.hi)), k.lo - std::max(1.0, std::abs(k.lo))}) {
                json v = x;
                if (k.type == KeyType::vec3) v = json::array({x, x, x});
                if (k.type == KeyType::int_pair) v = json::array({x, x});
                scene[at] = v;
                CHECK_THAT(error_of(scene), Catch::Contains(name) && Catch::Contains("is out of range [" ));
            }
        }
        if (!k.choices.empty()) {
            scene[at] = "bogus";
            CHECK_THAT(error_of(scene), Catch::Contains("\"" + name + "\" = \"bogus\" is not one of \"" + k.choices[0] + "\""));
        }
        if (k.required) {
            scene[at.parent_pointer()].erase(at.back());
            CHECK_THAT(error_of(scene), Catch::Contains("\"" + name + "\" must be given"));
        }
    }
}

TEST_CASE("scene keys: a default Scene is what a scene that sets nothing gets", "[scene-keys]") {
    // The table's defaults are read from scene.h's structs; this checks the way back, through parse().
    const Scene d;
    const Scene s = parse(R"({"particles": {"blocks": [{"max": [0.5, 0.5, 0.5]}]}})", "t");
    CHECK(s.sph.rest_density == d.sph.rest_density);
    CHECK(s.sph.max_density_error == d.sph.max_density_error);
    CHECK(s.sph.morton == d.sph.morton);
    CHECK(s.sph.solver == d.sph.solver);
    CHECK(s.turbulence.scale == d.turbulence.scale);
    CHECK(s.turbulence.lmin == d.turbulence.lmin);
    CHECK(s.turbulence.lmax == d.turbulence.lmax);
    CHECK(s.turbulence.subparticles.budget == d.turbulence.subparticles.budget);
    CHECK(s.surface.absorption == d.surface.absorption);
    CHECK(s.frame_dt == d.frame_dt);
    CHECK(s.substep_dt == d.substep_dt);
    CHECK(s.spacing == d.spacing);
    CHECK(s.particle_radius == 0.5f * d.spacing);
    CHECK(s.camera_eye == d.camera_eye);
    CHECK(s.light_dir == glm::normalize(d.light_dir));
    CHECK(s.model == d.model);
    CHECK(s.width == d.width);
}

TEST_CASE("scene keys: every bundled scene satisfies the schema, and the bad test scenes do not", "[scene-keys]") {
    const json schema = json::parse(json_schema());
    int scenes = 0;
    for (const auto& e : fs::directory_iterator(kSource / "media" / "scenes")) {
        if (e.path().extension() != ".json" || e.path().filename() == "scene.schema.json") continue;
        INFO(e.path().string());
        std::string why;
        CHECK(satisfies(json::parse(read(e.path())), schema, why));
        INFO(why);
        CHECK(why == "");
        ++scenes;
    }
    CHECK(scenes >= 5);
    for (const std::string bad : {"unknown-key.json", "out-of-range.json"}) {
        INFO(bad);
        std::string why;
        CHECK_FALSE(satisfies(json::parse(read(kSource / "tests" / "data" / "scenes" / bad)), schema, why));
    }
    std::string why;
    CHECK_FALSE(satisfies(json::parse(R"({"particles": {"blocks": []}})"), schema, why));   // at least one block
    CHECK_FALSE(satisfies(json::parse(R"({"particles": {"blocks": [{"max": [1, 1, 1]}]},
                                          "obstacles": [{"radius": 1, "min": [0, 0, 0]}]})"), schema, why));   // sphere and box
}
