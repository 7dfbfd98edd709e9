// Fuzz corpus: malformed scene files and command lines, each run through the real binary. Every one
// must exit 2 with one "ranryu: ..." line naming the file (or option) and, where there is one, the
// key; never crash (a signal, a sanitizer report), hang (a 30 s limit) or write anything.
//
// The scene corpus is made here from tests/data/scenes/small.json by a list of mutations, one or
// more per category: truncated JSON, wrong types, NaN and infinities, huge numbers, strings and
// arrays, zero and negative numbers, unknown keys, deep nesting, invalid UTF-8, empty files, and
// folders or devices where a file belongs. scripts/test.sh runs it again against the sanitizer build.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <functional>

#include <nlohmann/json.hpp>

#include "run_helper.h"

using namespace ranryu::test;
using nlohmann::json;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

const RunOptions kFuzzRun = [] {
    RunOptions o;
    o.timeout = std::chrono::seconds(30);
    return o;
}();

// Exit 2, one line on stderr naming every one of `names`, nothing on stdout, and `tmp` as it was.
void check_refused(const TempDir& tmp, const std::vector<std::string>& args, const std::vector<std::string>& names,
                   const std::vector<std::string>& tmp_entries) {
    RunOptions opt = kFuzzRun;
    const Result r = run_ranryu(tmp.path(), args, opt);
    INFO(r.describe());
    CHECK_FALSE(r.timed_out);
    CHECK(r.exit_code == 2);   // not 1 (an unexpected exception), not 128 + N (a signal)
    CHECK(r.err_lines().size() == 1);
    CHECK_THAT(r.err, StartsWith("ranryu: "));
    CHECK_THAT(r.err, !Contains("Sanitizer") && !Contains("runtime error"));
    for (const std::string& n : names) CHECK_THAT(r.err, Contains(n));
    CHECK(r.out.empty());
    CHECK(list_dir(tmp.path()) == tmp_entries);
}

std::string small_scene() { return read_file(scene_file("small.json")); }

// A mutation of small.json: the JSON changed by `edit`.
std::string edited(const std::function<void(json&)>& edit) {
    json j = json::parse(small_scene());
    edit(j);
    return j.dump(2);
}

// small.json with `text` added as its last member(s), as written: for what json cannot hold.
std::string appended(const std::string& text) {
    const std::string small = small_scene();
    return small.substr(0, small.rfind('}')) + ", " + text + "}\n";
}

struct SceneCase {
    std::string name;            // the file's name: its category and what is wrong
    std::string text;            // its bytes
    std::vector<std::string> names;   // besides the file, what the message must name (the key)
};

std::vector<SceneCase> scene_corpus() {
    const std::string small = small_scene();
    std::vector<SceneCase> c;
    // Truncated JSON: anywhere, the message says malformed and gives the line.
    for (const std::size_t at : {std::size_t(1), small.size() / 3, small.size() / 2, small.size() - 2})
        c.push_back({"truncated-" + std::to_string(at) + ".json", small.substr(0, at), {"malformed JSON", "line"}});
    c.push_back({"trailing-garbage.json", small + "}", {"malformed JSON"}});

    // Wrong types.
    c.push_back({"type-restitution-string.json", edited([](json& j) { j["tank"]["restitution"] = "0.5"; }), {"tank.restitution", "must be a number"}});
    c.push_back({"type-gravity-string.json", edited([](json& j) { j["gravity"] = "down"; }), {"gravity", "array of 3 numbers"}});
    c.push_back({"type-gravity-2.json", edited([](json& j) { j["gravity"] = {0, -9.81}; }), {"gravity", "array of 3 numbers"}});
    c.push_back({"type-gravity-nested.json", edited([](json& j) { j["gravity"] = {0, {1}, 0}; }), {"gravity", "array of 3 numbers"}});
    c.push_back({"type-blocks-object.json", edited([](json& j) { j["particles"]["blocks"] = json::object(); }), {"particles.blocks", "array of objects"}});
    c.push_back({"type-block-number.json", edited([](json& j) { j["particles"]["blocks"][0] = 3; }), {"particles.blocks[0]", "must be an object"}});
    c.push_back({"type-width-null.json", edited([](json& j) { j["render"]["width"] = nullptr; }), {"render.width", "must be a number"}});
    c.push_back({"type-width-fraction.json", edited([](json& j) { j["render"]["width"] = 64.5; }), {"render.width", "whole number"}});
    c.push_back({"type-model-number.json", edited([](json& j) { j["model"] = 3; }), {"model", "must be a string"}});
    c.push_back({"type-model-unknown.json", edited([](json& j) { j["model"] = "flip"; }), {"model", "is not one of"}});
    c.push_back({"type-closed-string.json", edited([](json& j) { j["tank"]["closed"] = "yes"; }), {"tank.closed", "true or false"}});
    c.push_back({"type-camera-array.json", edited([](json& j) { j["camera"] = json::array(); }), {"\"camera\" must be an object"}});
    c.push_back({"type-octaves.json", edited([](json& j) { j["turbulence"]["octaves"] = {5, 3}; }), {"turbulence.octaves", "lmin <= lmax"}});
    c.push_back({"type-solver.json", edited([](json& j) { j["sph"]["solver"] = "pcisph"; }), {"sph.solver", "is not one of"}});
    c.push_back({"root-array.json", "[1, 2, 3]", {"must be a JSON object"}});
    c.push_back({"root-number.json", "3", {"must be a JSON object"}});
    c.push_back({"root-null.json", "null", {"must be a JSON object"}});

    // NaN and infinities: not JSON, or beyond every bound.
    for (const std::string v : {"NaN", "nan", "Infinity", "-Infinity", "inf"})
        c.push_back({"nan-inf-" + v + ".json", "{\"tank\": {\"restitution\": " + v + "}}", {"malformed JSON"}});
    c.push_back({"overflow-1e999.json", "{\"tank\": {\"restitution\": 1e999}}", {"malformed JSON", "1e999"}});
    c.push_back({"overflow-neg-1e999.json", "{\"gravity\": [0, -1e999, 0]}", {"malformed JSON", "-1e999"}});

    // Huge numbers, strings, arrays and files.
    c.push_back({"huge-width.json", edited([](json& j) { j["render"]["width"] = 1e300; }), {"render.width", "out of range"}});
    c.push_back({"huge-seed.json", appended("\"turbulence\": {\"seed\": 18446744073709551616}"), {"turbulence.seed", "out of range"}});
    c.push_back({"huge-uint.json", appended("\"sph\": {\"max_substeps\": 18446744073709551615}"), {"sph.max_substeps", "out of range"}});
    c.push_back({"huge-particles.json", edited([](json& j) { j["particles"]["spacing"] = 0.0001; }), {"particles.spacing", "the limit is"}});
    c.push_back({"huge-string.json", edited([](json& j) { j["model"] = std::string(100000, 'x'); }), {"model", "is not one of"}});
    c.push_back({"huge-array.json", edited([](json& j) { j["gravity"] = json(std::vector<double>(100000, 1.0)); }), {"gravity", "array of 3 numbers"}});
    c.push_back({"huge-file.json", "{\"description\": \"" + std::string(2 << 20, 'x') + "\"}", {"bytes", "at most"}});

    // Zero and negative numbers.
    c.push_back({"zero-spacing.json", edited([](json& j) { j["particles"]["spacing"] = 0; }), {"particles.spacing", "out of range"}});
    c.push_back({"negative-spacing.json", edited([](json& j) { j["particles"]["spacing"] = -0.05; }), {"particles.spacing", "out of range"}});
    c.push_back({"zero-frame-dt.json", edited([](json& j) { j["time"]["frame_dt"] = 0; }), {"time.frame_dt", "out of range"}});
    c.push_back({"negative-substep.json", edited([](json& j) { j["time"]["substep_dt"] = -1; }), {"time.substep_dt", "out of range"}});
    c.push_back({"zero-width.json", edited([](json& j) { j["render"]["width"] = 0; }), {"render.width", "out of range"}});
    c.push_back({"negative-height.json", edited([](json& j) { j["render"]["height"] = -48; }), {"render.height", "out of range"}});
    c.push_back({"zero-tank.json", edited([](json& j) { j["tank"]["max"] = j["tank"]["min"]; }), {"tank.max", "must exceed"}});
    c.push_back({"negative-block.json", edited([](json& j) { j["particles"]["blocks"][0]["max"] = {0.0, 0.0, 0.0}; }),
                 {"particles.blocks[0].max", "must exceed"}});
    c.push_back({"zero-light.json", edited([](json& j) { j["light"]["direction"] = {0, 0, 0}; }), {"light.direction", "not be zero"}});
    c.push_back({"zero-radius.json", edited([](json& j) { j["obstacles"] = {{{"center", {0.5, 0.5, 0.5}}, {"radius", 0}}}; }),
                 {"obstacles[0].radius", "out of range"}});
    c.push_back({"zero-iterations.json", edited([](json& j) { j["sph"]["max_iterations"] = 0; }), {"sph.max_iterations", "out of range"}});
    // The step the iterations allow (docs/DFSPH.md (D8)): its band must be one, and reachable.
    c.push_back({"step-band-inverted.json", edited([](json& j) { j["sph"]["shrink_step_above"] = 10; j["sph"]["grow_step_below"] = 10; }),
                 {"sph.grow_step_below", "must be below", "sph.shrink_step_above"}});
    c.push_back({"step-band-below-least.json", edited([](json& j) { j["sph"]["shrink_step_above"] = 3; j["sph"]["grow_step_below"] = 1;
                                                                    j["sph"]["min_iterations"] = 5; }),
                 {"sph.min_iterations", "must not exceed", "sph.shrink_step_above"}});
    c.push_back({"negative-zero-substeps.json", edited([](json& j) { j["sph"]["max_substeps"] = -0.0; }), {"sph.max_substeps", "out of range"}});
    c.push_back({"no-blocks.json", "{}", {"particles.blocks", "at least one block"}});
    c.push_back({"empty-blocks.json", edited([](json& j) { j["particles"]["blocks"] = json::array(); }), {"particles.blocks", "at least one block"}});

    // Unknown keys, at every depth.
    c.push_back({"unknown-top.json", edited([](json& j) { j["colour"] = "blue"; }), {"unknown key \"colour\""}});
    c.push_back({"unknown-sph.json", edited([](json& j) { j["sph"]["viscosityy"] = 1; }), {"unknown key \"sph.viscosityy\""}});
    c.push_back({"unknown-block.json", edited([](json& j) { j["particles"]["blocks"][0]["speed"] = 1; }),
                 {"unknown key \"particles.blocks[0].speed\""}});
    c.push_back({"unknown-subparticles.json", edited([](json& j) { j["turbulence"]["subparticles"]["level"] = 1; }),
                 {"unknown key \"turbulence.subparticles.level\""}});
    c.push_back({"unknown-empty-key.json", edited([](json& j) { j[""] = 1; }), {"unknown key \"\""}});
    c.push_back({"unknown-sphere-and-box.json",
                 edited([](json& j) { j["obstacles"] = {{{"radius", 0.1}, {"min", {0, 0, 0}}}}; }), {"unknown key \"obstacles[0].min\""}});

    // Deep nesting.
    c.push_back({"deep-array.json", "{\"sph\": " + std::string(100000, '[') + std::string(100000, ']') + "}", {"nested deeper"}});
    c.push_back({"deep-object.json", [] {
                     std::string s;
                     for (int i = 0; i < 50000; ++i) s += "{\"a\":";
                     return s + "1" + std::string(50000, '}');
                 }(), {"nested deeper"}});
    c.push_back({"deep-unclosed.json", std::string((1 << 20) + 1, '['), {"bytes"}});   // over the size limit before anything
    c.push_back({"deep-unclosed-small.json", std::string(500000, '['), {"nested deeper"}});

    // Invalid UTF-8 and other bytes.
    c.push_back({"utf8-value.json", "{\"description\": \"caf\xe9\"}", {"malformed JSON"}});
    c.push_back({"utf8-key.json", "{\"\xff\xfe\": 1}", {"malformed JSON"}});
    c.push_back({"utf16-bom.json", std::string("\xff\xfe{\0}\0", 6), {"malformed JSON"}});
    c.push_back({"nul-byte.json", std::string("{\"name\": \"a\0b\"}", 15), {"malformed JSON"}});
    c.push_back({"control-char.json", "{\"name\": \"a\x01" "b\"}", {"malformed JSON"}});

    // Empty files.
    c.push_back({"empty.json", "", {"malformed JSON"}});
    c.push_back({"whitespace.json", " \n\t\n", {"malformed JSON"}});
    return c;
}

}  // namespace

TEST_CASE("fuzz: every malformed scene file exits 2 naming the file and the key, and writes nothing", "[cli][fuzz]") {
    TempDir corpus;   // the files, apart from the folder the command runs in (which must stay empty)
    for (const SceneCase& c : scene_corpus()) {
        DYNAMIC_SECTION(c.name) {
            const std::string path = corpus.str(c.name);
            write_file(path, c.text);
            TempDir tmp;
            for (const std::string cmd : {"record", "profile", "validate"}) {
                INFO(cmd << " --scene " << c.name);
                std::vector<std::string> args = {cmd};
                if (cmd == "validate") args.push_back("hydrostatic");
                for (const std::string a : {"--scene", path.c_str()}) args.push_back(a);
                if (cmd == "record") args.insert(args.end(), {"--frames", "1", "--out", tmp.str("out")});
                if (cmd == "profile") args.insert(args.end(), {"--frames", "1", "--json", tmp.str("p.json")});
                std::vector<std::string> names = c.names;
                names.push_back(path);
                check_refused(tmp, args, names, {});
            }
        }
    }
}

TEST_CASE("fuzz: a folder, a device or a pipe where a scene file belongs exits 2 and writes nothing", "[cli][fuzz]") {
    TempDir tmp;
    fs::create_directory(tmp / "folder.json");
    REQUIRE(mkfifo(tmp.str("pipe.json").c_str(), 0600) == 0);   // would block a reader for ever
    const std::vector<std::string> entries = {"folder.json", "pipe.json"};
    check_refused(tmp, {"record", "--scene", tmp.str("folder.json"), "--frames", "1", "--out", tmp.str("out")},
                  {tmp.str("folder.json"), "folder"}, entries);
    check_refused(tmp, {"record", "--scene", tmp.str("folder.json") + "/", "--frames", "1", "--out", tmp.str("out")},
                  {tmp.str("folder.json"), "folder"}, entries);
    check_refused(tmp, {"profile", "--scene", tmp.str("pipe.json"), "--frames", "1"}, {tmp.str("pipe.json"), "not a regular file"}, entries);
    check_refused(tmp, {"validate", "dam-break", "--scene", "/dev/zero"}, {"/dev/zero", "not a regular file"}, entries);
    check_refused(tmp, {"record", "--scene", "/dev/null", "--out", tmp.str("out")}, {"/dev/null", "not a regular file"}, entries);
    // Output files where a folder is, and a folder where a file is.
    check_refused(tmp, {"export-field", "--out", tmp.str("folder.json"), "--force"}, {"--out " + tmp.str("folder.json"), "folder"}, entries);
    check_refused(tmp, {"record", "--scene", scene_file("small.json").string(), "--out", tmp.str("pipe.json")},
                  {"--out " + tmp.str("pipe.json")}, entries);
}

TEST_CASE("fuzz: malformed command lines exit 2 naming the option, for every command", "[cli][fuzz]") {
    TempDir tmp;
    const std::string scene = scene_file("small.json").string();
    const std::string long_arg(100000, 'x');
    const std::string bad_utf8 = "\xff\xfe";
    // {args, what the message names}
    const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
        {{""}, {"unknown command"}},
        {{"-"}, {"unknown command"}},
        {{"--"}, {"unknown command"}},
        {{bad_utf8}, {"unknown command"}},
        {{long_arg}, {"unknown command"}},
        {{"scenes", "extra"}, {"extra"}},
        {{"scenes", "--schema", "--markdown"}, {"--schema", "--markdown"}},
        {{"scenes", "--schema=1"}, {"--schema", "takes no value"}},
        {{"record", "--"}, {"unknown option --"}},
        {{"record", "--=x"}, {"unknown option"}},
        {{"record", "-x"}, {"-x"}},
        {{"record", "--frames"}, {"--frames", "needs a value"}},
        {{"record", "--frames="}, {"--frames", "needs a value"}},
        {{"record", "--scene="}, {"--scene", "needs a value"}},
        {{"record", "--scene", ""}, {"--scene", "needs a value"}},
        {{"record", "--scene", bad_utf8}, {bad_utf8}},
        {{"record", "--scene", long_arg}, {"no bundled scene"}},
        {{"record", "--scene", "/" + long_arg + ".json"}, {"cannot read"}},
        {{"record", "--spacing", "nan"}, {"--spacing nan"}},
        {{"record", "--spacing", "inf"}, {"--spacing inf"}},
        {{"record", "--spacing", "-inf"}, {"--spacing -inf"}},
        {{"record", "--spacing", "1e-999"}, {"--spacing 1e-999"}},
        {{"record", "--spacing", "1e999"}, {"--spacing 1e999"}},
        {{"record", "--spacing", ""}, {"--spacing", "needs a value"}},
        {{"record", "--frames", "nan"}, {"--frames nan"}},
        {{"record", "--frames", "1e3"}, {"--frames 1e3"}},
        {{"record", "--frames", "0x10"}, {"--frames 0x10"}},
        {{"record", "--frames", "+1"}, {"--frames +1"}},
        {{"record", "--frames", "99999999999999999999"}, {"--frames 99999999999999999999"}},
        {{"record", "--frames", "-2147483648"}, {"--frames -2147483648"}},
        {{"record", "--size", "nanxnan"}, {"--size nanxnan"}},
        {{"record", "--size", "1e3x1e3"}, {"--size 1e3x1e3"}},
        {{"record", "--size", "99999999999x64"}, {"--size 99999999999x64"}},
        {{"record", "--size", "x"}, {"--size x"}},
        {{"record", "--solver", "DFSPH"}, {"--solver DFSPH"}},
        {{"record", "--scene", scene, "--solver", "wcsph"}, {"--solver wcsph", "ballistic"}},
        {{"record", "--shading", "wireframe"}, {"--shading wireframe"}},
        {{"record", "--scene", scene, "--export-mesh"}, {"--export-mesh"}},
        {{"record", "--force=yes"}, {"--force", "takes no value"}},
        {{"record", "--quiet=1"}, {"--quiet", "takes no value"}},
        {{"record", "--shader-dir", "/nonexistent-ranryu"}, {"--shader-dir /nonexistent-ranryu"}},
        {{"profile", "--warmup", "-1"}, {"--warmup -1"}},
        {{"profile", "--warmup", "inf"}, {"--warmup inf"}},
        {{"profile", "--out", "x"}, {"unknown option --out"}},
        {{"profile", "--json"}, {"--json", "needs a value"}},
        {{"profile", "--frames", "0"}, {"--frames 0"}},
        {{"validate"}, {"validate"}},
        {{"validate", "--quiet"}, {"validate"}},
        {{"validate", "bogus"}, {"bogus"}},
        {{"validate", "dam-break", "extra"}, {"extra"}},
        {{"validate", "dam-break", "--spacing", "0"}, {"--spacing 0"}},
        {{"validate", "dam-break", "--solver", ""}, {"--solver", "needs a value"}},
        {{"validate", "dam-break", "--frames", "1"}, {"unknown option --frames"}},
        {{"validate", "dam-break", "--relax"}, {"--relax", "only the hydrostatic case"}},
        {{"validate", "dam-break", "--average", "1"}, {"--average", "only the hydrostatic case"}},
        {{"validate", "standing-wave", "--settle", "1"}, {"--settle", "only the hydrostatic case"}},
        {{"validate", "hydrostatic", "--settle", "-1"}, {"--settle -1"}},
        {{"validate", "hydrostatic", "--settle", "nan"}, {"--settle nan"}},
        {{"validate", "hydrostatic", "--average", "0"}, {"--average 0"}},
        {{"validate", "hydrostatic", "--average", "61"}, {"--average 61"}},
        {{"export-field"}, {"--out"}},
        {{"export-field", "--out", "f.npy", "--size", "7"}, {"--size 7"}},
        {{"export-field", "--out", "f.npy", "--size", "257"}, {"--size 257"}},
        {{"export-field", "--out", "f.npy", "--extent", "0"}, {"--extent 0"}},
        {{"export-field", "--out", "f.npy", "--extent", "nan"}, {"--extent nan"}},
        {{"export-field", "--out", "f.npy", "--beta", "-inf"}, {"--beta -inf"}},
        {{"export-field", "--out", "f.npy", "--seed", "-1"}, {"--seed -1"}},
        {{"export-field", "--out", "f.npy", "--seed", "4294967296"}, {"--seed 4294967296"}},
        {{"export-field", "--out", "f.npy", "--octaves", "5:3"}, {"--octaves 5:3"}},
        {{"export-field", "--out", "f.npy", "--octaves", "1:"}, {"--octaves 1:"}},
        {{"export-field", "--out", "f.npy", "--octaves", ":"}, {"--octaves :"}},
        {{"export-field", "--out", "f.npy", "--octaves", "a:b"}, {"--octaves a:b"}},
        {{"export-field", "--out", "no/such/folder/f.npy"}, {"--out no/such/folder/f.npy"}},
        {{"export-field", "--out", "f.npy", "--scene", "drop"}, {"unknown option --scene"}},
        {{"run", "--frames", "-1"}, {"--frames -1"}},
#if RANRYU_HAVE_WINDOW
        {{"run", "--screenshot", "/nonexistent-ranryu/x.png", "--frames", "1"}, {"--screenshot /nonexistent-ranryu/x.png"}},
#endif
        {{"run", "--out", "x"}, {"unknown option --out"}},
    };
    for (const auto& [args, names] : cases) {
        std::string line;
        for (const std::string& a : args) line += " " + (a.size() > 40 ? a.substr(0, 40) + "..." : a);
        INFO("ranryu" << line);
        std::vector<std::string> expect = names;
        for (std::string& n : expect)
            if (n.size() > 200) n = n.substr(0, 200);   // a message may show a long argument cut short
        check_refused(tmp, args, expect, {});
    }
}
