// Bad input: each mistake exits 2 with exactly one line on stderr ("ranryu: ...") that names the
// input at fault, prints nothing on stdout (it is caught before any GPU work) and leaves nothing behind.
#include <catch2/catch.hpp>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::StartsWith;

namespace {

// Exit code 2, one "ranryu: ..." line on stderr that contains every one of `names`.
void check_bad_input(const Result& r, const std::vector<std::string>& names, bool stdout_empty = true) {
    INFO(r.describe());
    CHECK(r.exit_code == 2);
    CHECK(r.err_lines().size() == 1);
    CHECK_THAT(r.err, StartsWith("ranryu: "));
    CHECK_THAT(r.err, EndsWith("\n"));
    for (const std::string& name : names) CHECK_THAT(r.err, Contains(name));
    if (stdout_empty) CHECK(r.out.empty());
}

// `ranryu record` of `scene` into TMP/out: refused, and TMP/out never made.
void check_bad_scene(const std::string& scene, const std::vector<std::string>& names) {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene, "--size", "64x48", "--frames", "1", "--out", tmp.str("out")});
    check_bad_input(r, names);
    CHECK_FALSE(fs::exists(tmp / "out"));
}

}  // namespace

// ---- scenes ----

TEST_CASE("bad input: an unknown scene name", "[cli][bad-input]") {
    check_bad_scene("no-such-scene", {"no-such-scene", "falling-block"});   // names the bundled ones too
    TempDir tmp;
    check_bad_input(run_ranryu(tmp.path(), {"profile", "--scene", "no-such-scene"}), {"no-such-scene"});
}

TEST_CASE("bad input: a scene file that does not exist", "[cli][bad-input]") {
    const std::string path = scene_file("no-such-file.json").string();
    check_bad_scene(path, {path});
}

TEST_CASE("bad input: a malformed JSON scene names the file and the line", "[cli][bad-input]") {
    // tests/data/scenes/malformed.json: a trailing comma in "tank", on line 4.
    const std::string path = scene_file("malformed.json").string();
    check_bad_scene(path, {path, "line 4"});
}

TEST_CASE("bad input: an unknown key in a scene", "[cli][bad-input]") {
    const std::string path = scene_file("unknown-key.json").string();
    check_bad_scene(path, {path, "unknown key", "particles.spaceing"});
}

TEST_CASE("bad input: an out-of-range value in a scene", "[cli][bad-input]") {
    const std::string path = scene_file("out-of-range.json").string();
    check_bad_scene(path, {path, "tank.restitution", "1.5", "out of range"});
}

TEST_CASE("bad input: PBF's iterations or substeps below one are refused by name", "[cli][bad-input][pbf]") {
    TempDir tmp;
    const auto [key, value] = GENERATE(std::pair<std::string, std::string>{"iterations", "0"}, std::pair<std::string, std::string>{"iterations", "-3"},
                                       std::pair<std::string, std::string>{"substeps", "0"});
    const fs::path path = tmp / "pbf.json";
    write_file(path, R"({"model": "sph", "sph": {"solver": "pbf", "pbf": {")" + key + "\": " + value +
                         R"(}}, "particles": {"blocks": [{"max": [0.2, 0.2, 0.2]}]}})");
    check_bad_scene(path.string(), {path.string(), "sph.pbf." + key, value, "out of range"});
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--solver", "pbd", "--frames", "1", "--out", tmp.str("out")});
    check_bad_input(r, {"--solver pbd", "dfsph, wcsph or pbf"});
}

// ---- options ----

TEST_CASE("bad input: --spacing outside [0.0001, 1] m or one that leaves no particle", "[cli][bad-input]") {
    TempDir tmp;
    for (const std::string dx : {"0", "-0.01", "abc", "2", "0.01m"}) {
        INFO("--spacing " << dx);
        check_bad_input(run_ranryu(tmp.path(), {"record", "--spacing", dx, "--frames", "1", "--out", tmp.str("out")}),
                        {"--spacing " + dx});
    }
    // Coarser than the dam break's 0.2 x 0.4 x 0.1 m column: no particle fits in its block.
    check_bad_input(run_ranryu(tmp.path(), {"profile", "--scene", "dam-break", "--spacing", "0.5", "--frames", "1"}),
                    {"--spacing", "no particle"});
}

TEST_CASE("bad input: neighbour masks larger than one storage block name the key to turn off", "[cli][bad-input]") {
    // llvmpipe's storage blocks hold 128 MiB (GL_MAX_SHADER_STORAGE_BLOCK_SIZE), and the shaders index
    // the masks with 32-bit uints: the dam break at 1.5 mm (2.3M particles) has fluid masks of 336 MB;
    // a 1 m tank at 4 mm has 955,608 boundary particles, whose DFSPH rows' masks (27 runs with Morton
    // keys) take 206 MB. Both are refused before any output exists (engine/sim/fluid.cpp, dfsph.cpp).
    // A device whose storage blocks hold them (NVIDIA's: 2 GiB) runs these scenes: that part is skipped
    // there, after checking that the run did write its frame. On llvmpipe the refusal is required.
    TempDir tmp;
    auto refused = [&](const Result& r, const char* what) {
        if (r.exit_code != 0 || r.out.find("llvmpipe") != std::string::npos || r.err.find("llvmpipe") != std::string::npos) return true;
        CHECK(fs::exists(tmp / "out" / "frame_00000.png"));
        WARN("skipped: this device's storage blocks hold " << what << " (the refusal is checked where they do not, as on llvmpipe)");
        fs::remove_all(tmp / "out");
        return false;
    };
    Result r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--spacing", "0.0015", "--size", "64x48", "--frames", "1",
                                       "--out", tmp.str("out")});
    if (refused(r, "the dam break's masks at 1.5 mm")) {
        check_bad_input(r, {"scene dam-break", "neighbour masks", "storage block", "\"neighbour_masks\": false"}, false);
        CHECK_FALSE(fs::exists(tmp / "out"));
    }
    const fs::path path = tmp / "tank.json";
    write_file(path, R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "sph": {"solver": "dfsph", "boundary_rows": true, "neighbour_keys": "morton", "neighbour_masks": false},
        "particles": {"spacing": 0.004, "blocks": [{"min": [0, 0, 0], "max": [0.04, 0.04, 0.04]}]}})");
    r = run_ranryu(tmp.path(), {"record", "--scene", path.string(), "--size", "64x48", "--frames", "1", "--out", tmp.str("out")});
    if (refused(r, "the 1 m tank's boundary rows' masks")) {
        check_bad_input(r, {path.string(), "boundary rows' neighbour masks", "storage block", "\"boundary_rows\": false"}, false);
        CHECK_FALSE(fs::exists(tmp / "out"));
    }
}

TEST_CASE("bad input: validate without a case or with an unknown one", "[cli][bad-input]") {
    TempDir tmp;
    check_bad_input(run_ranryu(tmp.path(), {"validate"}), {"validate", "dam-break"});
    check_bad_input(run_ranryu(tmp.path(), {"validate", "bogus"}), {"bogus", "dam-break", "hydrostatic"});
    check_bad_input(run_ranryu(tmp.path(), {"validate", "dam-break", "--spacing", "-1"}), {"--spacing -1"});
}

TEST_CASE("bad input: --size 0x0 and other sizes that are not WIDTHxHEIGHT in [16, 8192]", "[cli][bad-input]") {
    TempDir tmp;
    for (const std::string size : {"0x0", "64", "64x", "x48", "15x48", "64x8193", "axb", "64x48x2", "-64x48"}) {
        for (const std::string cmd : {"record", "profile"}) {
            INFO(cmd << " --size " << size);
            check_bad_input(run_ranryu(tmp.path(), {cmd, "--size", size, "--frames", "1", "--out", tmp.str("out")}),
                            {"--size " + size});
        }
    }
    CHECK_FALSE(fs::exists(tmp / "out"));
}

TEST_CASE("bad input: record --frames 0 and other frame counts that are not whole numbers >= 1", "[cli][bad-input]") {
    TempDir tmp;
    for (const std::string frames : {"0", "-1", "abc", "2.5", "1000001"}) {
        INFO("--frames " << frames);
        check_bad_input(run_ranryu(tmp.path(), {"record", "--frames", frames, "--size", "64x48", "--out", tmp.str("out")}),
                        {"--frames " + frames});
    }
    CHECK_FALSE(fs::exists(tmp / "out"));
}

TEST_CASE("bad input: an unknown command", "[cli][bad-input]") {
    TempDir tmp;
    check_bad_input(run_ranryu(tmp.path(), {"frobnicate"}), {"unknown command", "frobnicate"});
    check_bad_input(run_ranryu(tmp.path(), {"frobnicate", "--frames", "1"}), {"unknown command", "frobnicate"});
}

TEST_CASE("bad input: an unknown option", "[cli][bad-input]") {
    TempDir tmp;
    check_bad_input(run_ranryu(tmp.path(), {"record", "--bogus", "1", "--out", tmp.str("out")}), {"unknown option", "--bogus"});
    check_bad_input(run_ranryu(tmp.path(), {"profile", "--bogus=1"}), {"unknown option", "--bogus"});
    // An option another command takes.
    check_bad_input(run_ranryu(tmp.path(), {"profile", "--out", tmp.str("out")}), {"unknown option", "--out"});
    check_bad_input(run_ranryu(tmp.path(), {"record", "--warmup", "3", "--out", tmp.str("out")}), {"unknown option", "--warmup"});
    check_bad_input(run_ranryu(tmp.path(), {"record", "stray", "--out", tmp.str("out")}), {"stray"});
    CHECK_FALSE(fs::exists(tmp / "out"));
}

TEST_CASE("bad input: an unknown option last on the line is reported as unknown", "[cli][bad-input]") {
    // "ranryu record --bogus" must say that --bogus is unknown, not that it "needs a value" (which
    // sends the user looking for a value to give an option that does not exist).
    TempDir tmp;
    check_bad_input(run_ranryu(tmp.path(), {"record", "--out", tmp.str("out"), "--bogus"}), {"unknown option", "--bogus"});
    check_bad_input(run_ranryu(tmp.path(), {"scenes", "--bogus"}), {"unknown option", "--bogus"});
    CHECK_FALSE(fs::exists(tmp / "out"));
}

TEST_CASE("bad input: a flag given a value is refused and --force=no deletes nothing", "[cli][bad-input]") {
    // --force and --gl-debug take no value. "--force=no" must not be read as --force: that would
    // delete the earlier run the user meant to keep.
    TempDir tmp;
    const std::string out = tmp.str("out");
    const std::vector<std::string> base = {"record", "--scene", scene_file("small.json").string(), "--frames", "1", "--out", out};
    REQUIRE(run_ranryu(tmp.path(), base).exit_code == 0);
    const std::string frame = read_file(tmp / "out" / "frame_00000.png");
    const std::string run_json = read_file(tmp / "out" / "run.json");
    for (const std::string flag : {"--force=no", "--force=false", "--gl-debug=0"}) {
        INFO(flag);
        std::vector<std::string> args = base;
        args.push_back(flag);
        check_bad_input(run_ranryu(tmp.path(), args), {flag.substr(0, flag.find('='))});
        CHECK(read_file(tmp / "out" / "frame_00000.png") == frame);
        CHECK(read_file(tmp / "out" / "run.json") == run_json);
    }
}

TEST_CASE("bad input: an option without its value", "[cli][bad-input]") {
    TempDir tmp;
    check_bad_input(run_ranryu(tmp.path(), {"record", "--out"}), {"--out", "needs a value"});
    check_bad_input(run_ranryu(tmp.path(), {"record", "--out="}), {"--out", "needs a value"});
    check_bad_input(run_ranryu(tmp.path(), {"profile", "--json="}), {"--json", "needs a value"});
}

// ---- output paths ----

TEST_CASE("bad input: an --out folder that cannot be made or written", "[cli][bad-input]") {
    TempDir tmp;
    write_file(tmp / "blocker", "a regular file\n");
    // Tests may run as root, for whom permission bits do not block writes: use paths that no user can
    // make, a folder under a regular file, or write into: /proc.
    std::vector<std::string> outs = {tmp.str("blocker/sub"), tmp.str("blocker/sub/deeper"),
                                     tmp.str("blocker")};   // the last: exists and is not a folder
    if (fs::is_directory("/proc/self")) {
        outs.push_back("/proc/ranryu-cli-test-out");   // cannot be created
        outs.push_back("/proc/self");                   // exists, cannot be written
    } else {
        WARN("no /proc: skipping the /proc cases");
    }
    for (const std::string& out : outs) {
        INFO("--out " << out);
        check_bad_input(run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--frames", "1",
                                                "--out", out}),
                        {"--out " + out});
    }
    CHECK(read_file(tmp / "blocker") == "a regular file\n");
    CHECK(list_dir(tmp.path()) == std::vector<std::string>{"blocker"});
}

TEST_CASE("bad input: a report file that cannot be written is refused before the run, naming why", "[cli][bad-input]") {
    // profile::check_writable(): every --json, --csv and --records (and record's, validate's) is tried
    // before any work, so that no run is spent, nor an earlier one removed, for a file it cannot write.
    TempDir tmp;
    write_file(tmp / "blocker", "a regular file\n");
    fs::create_directory(tmp / "folder");
    const std::string small = scene_file("small.json").string();
    for (const std::string opt : {"--json", "--csv", "--records"}) {
        const std::string under_file = tmp.str("blocker/report"), folder = tmp.str("folder");
        INFO(opt);
        check_bad_input(run_ranryu(tmp.path(), {"profile", "--scene", small, "--frames", "1", "--warmup", "0", opt, under_file}),
                        {opt + " " + under_file, tmp.str("blocker") + " is not a folder"});
        check_bad_input(run_ranryu(tmp.path(), {"profile", "--scene", small, "--frames", "1", "--warmup", "0", opt, folder}),
                        {opt + " " + folder, "is a folder"});
        check_bad_input(run_ranryu(tmp.path(), {"profile", "--scene", small, "--frames", "1", "--warmup", "0", opt, tmp.str("none/r")}),
                        {opt + " " + tmp.str("none/r"), "its folder " + tmp.str("none") + " does not exist"});
    }
    check_bad_input(run_ranryu(tmp.path(), {"validate", "hydrostatic", "--spacing", "0.04", "--json", tmp.str("blocker/v.json")}),
                    {"--json " + tmp.str("blocker/v.json")});
    // sweep's rows files, before its first row runs.
    fs::create_directories(tmp / "sweep" / "sweep.csv");
    check_bad_input(run_ranryu(tmp.path(), {"sweep", "--quick", "--out", tmp.str("sweep")}), {"--out " + tmp.str("sweep"), "sweep.csv", "is a folder"});
    CHECK(list_dir(tmp / "sweep") == std::vector<std::string>{"sweep.csv"});
    CHECK(list_dir(tmp.path()) == (std::vector<std::string>{"blocker", "folder", "sweep"}));
    CHECK(list_dir(tmp / "folder").empty());
}

TEST_CASE("bad input: record --force with a --records it cannot write keeps the earlier run", "[cli][bad-input]") {
    TempDir tmp;
    const std::vector<std::string> run = {"record", "--scene", scene_file("small.json").string(), "--frames", "1", "--out", tmp.str("out")};
    const Result first = run_ranryu(tmp.path(), run);
    INFO(first.describe());
    REQUIRE(first.exit_code == 0);
    const std::vector<std::string> earlier = list_dir(tmp / "out");
    REQUIRE(earlier.size() >= 2);   // a frame and run.json
    const std::string report = read_file(tmp / "out" / "run.json");
    std::vector<std::string> again = run;
    again.insert(again.end(), {"--force", "--records", tmp.str("out/run.json/records.csv")});
    check_bad_input(run_ranryu(tmp.path(), again), {"--records " + tmp.str("out/run.json/records.csv")});
    CHECK(list_dir(tmp / "out") == earlier);
    CHECK(read_file(tmp / "out" / "run.json") == report);
}

// ---- run --script, --shots ----

TEST_CASE("bad input: a run script with a mistake names the file and the line, before any window", "[cli][bad-input][script]") {
    if (!RANRYU_HAVE_WINDOW) {   // `run` itself is refused in a headless build (tests/cli/window_test.cpp)
        WARN("skipped: this build has no window (GLFW was not found at configure time)");
        return;
    }
    TempDir tmp;
    write_file(tmp / "s.txt", "# a comment\n0 key h\n2 key q\n");
    // No display: the refusal comes before a window is opened.
    const RunOptions no_display{.cwd = tmp.path(), .timeout = std::chrono::seconds(60), .unset_env = {"DISPLAY", "WAYLAND_DISPLAY"}, .set_env = {}};
    check_bad_input(run_ranryu(tmp.path(), {"run", "--script", "s.txt"}, no_display), {"--script s.txt:3:", "key q"});
    check_bad_input(run_ranryu(tmp.path(), {"run", "--script", "missing.txt"}, no_display), {"--script missing.txt", "cannot read"});
    write_file(tmp / "shots", "a file, not a folder\n");
    check_bad_input(run_ranryu(tmp.path(), {"run", "--shots", "shots"}, no_display), {"--shots shots", "not a folder"});
    CHECK(list_dir(tmp.path()) == std::vector<std::string>{"s.txt", "shots"});
}
