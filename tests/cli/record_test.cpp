// ranryu record: exactly the frames asked for as PNGs of the asked size with real content, plus
// run.json; an earlier run in the folder is refused (and left as it was) unless --force.
#include <catch2/catch.hpp>

#include <cstdio>
#include <map>

#include <nlohmann/json.hpp>

#include "image.h"
#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

std::string frame_name(int i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "frame_%05d.png", i);
    return buf;
}

// The names a run of `frames` frames leaves: frame_00000.png ... and run.json, sorted.
std::vector<std::string> expected_files(int frames) {
    std::vector<std::string> names;
    for (int i = 0; i < frames; ++i) names.push_back(frame_name(i));
    names.push_back("run.json");
    return names;
}

Result record(const TempDir& tmp, const std::string& out, int frames, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"record", "--scene", scene_file("small.json").string(), "--size", "64x48",
                                     "--frames", std::to_string(frames), "--out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_ranryu(tmp.path(), args);
}

// Every file of the folder, by name, with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const std::string& name : list_dir(dir)) files[name] = read_file(dir / name);
    return files;
}

}  // namespace

TEST_CASE("ranryu record writes exactly the frames asked as non-blank PNGs of the asked size", "[cli][record]") {
    TempDir tmp;
    const int frames = 5;   // more than the recorder's ring of 3 read-back buffers
    const Result r = record(tmp, tmp.str("out"), frames);
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("wrote 5 frames (64x48)"));
    CHECK_THAT(r.err, !Contains("GL error"));   // Debug builds report every GL error on stderr

    REQUIRE(list_dir(tmp / "out") == expected_files(frames));
    std::vector<std::vector<std::uint8_t>> pixels;
    for (int i = 0; i < frames; ++i) {
        const Image img = load_png(tmp / "out" / frame_name(i));
        INFO(frame_name(i) << ": " << img.error << ", " << img.distinct_colours() << " colours, luma sd "
                           << img.luma_stddev());
        REQUIRE(img.ok());
        CHECK(img.width == 64);
        CHECK(img.height == 48);
        // A rendered scene (background, floor, tank edges, shaded particles), not a cleared or empty
        // image: a real frame of this scene has hundreds of colours.
        CHECK(img.distinct_colours() >= 16);
        CHECK(img.luma_stddev() > 2.0);
        pixels.push_back(img.rgba);
    }
    // The block is thrown sideways at 3 m/s: the last frame differs from the first (frames are not
    // one buffer written five times).
    CHECK(pixels.front() != pixels.back());
}

TEST_CASE("ranryu record writes run.json describing the run", "[cli][record]") {
    TempDir tmp;
    const Result r = record(tmp, tmp.str("out"), 3);
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
    INFO(j.dump(2));
    CHECK(j["scene"] == "cli-small");
    CHECK(j["scene_origin"] == scene_file("small.json").string());
    CHECK(j["width"] == 64);
    CHECK(j["height"] == 48);
    CHECK(j["frames"] == 3);
    CHECK(j["frames_written"] == 3);
    CHECK(j["frame_pattern"] == "frame_%05d.png");
    CHECK(j["particles"] == 144);
    // small.json: frame_dt 0.02 s in substeps of 0.005 s.
    REQUIRE(j["simulated_seconds_per_frame"].is_number());
    CHECK(j["simulated_seconds_per_frame"].get<double>() == Approx(0.02).epsilon(1e-5));
    CHECK(j["substeps_per_frame"] == 4);
    REQUIRE(j["simulated_seconds"].is_number());
    CHECK(j["simulated_seconds"].get<double>() == Approx(3 * 0.02).epsilon(1e-5));
    for (const char* key : {"device", "driver", "date"}) {
        INFO("key " << key);
        REQUIRE(j[key].is_string());
        CHECK(!j[key].get<std::string>().empty());
    }
    // Per-pass timings: the frame passes and the read-back, each with numbers >= 0.
    REQUIRE(j["passes"].is_array());
    std::vector<std::string> names;
    for (const auto& p : j["passes"]) {
        INFO(p.dump());
        names.push_back(p.at("name").get<std::string>());
        for (const char* key : {"calls_per_frame", "min_ms", "median_ms", "max_ms", "share"}) {
            INFO("key " << key);
            REQUIRE(p.at(key).is_number());
            CHECK(p.at(key).get<double>() >= 0.0);
        }
    }
    for (const char* pass : {"ballistic.integrate", "clear", "draw-floor", "draw-tank", "draw-particles", "readback"}) {
        INFO("pass " << pass);
        CHECK(std::find(names.begin(), names.end(), pass) != names.end());
    }
}

TEST_CASE("ranryu record into a folder holding an earlier run is refused and leaves it unchanged", "[cli][record]") {
    TempDir tmp;
    const std::string out = tmp.str("out");
    const Result first = record(tmp, out, 3);
    INFO("first run:\n" << first.describe());
    REQUIRE(first.exit_code == 0);
    const auto before = snapshot(out);
    REQUIRE(before.size() == 4);

    const Result second = record(tmp, out, 2);
    INFO("second run:\n" << second.describe());
    CHECK(second.exit_code == 2);
    REQUIRE(second.err_lines().size() == 1);
    CHECK_THAT(second.err, Contains("--out " + out));
    CHECK_THAT(second.err, Contains("--force"));
    CHECK(second.out.empty());   // refused before any GPU work
    // Byte for byte the first run's files, and nothing else.
    CHECK(snapshot(out) == before);
}

TEST_CASE("ranryu record --force replaces an earlier run", "[cli][record]") {
    TempDir tmp;
    const std::string out = tmp.str("out");
    REQUIRE(record(tmp, out, 3).exit_code == 0);
    // Something of the user's in the same folder is no part of a run and must survive.
    write_file(tmp / "out" / "notes.txt", "mine\n");

    const Result r = record(tmp, out, 2, {"--force"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, !Contains("GL error"));
    CHECK_THAT(r.out, Contains("--force: removed 4 files"));
    // The earlier 3 frames and run.json are gone, not overwritten in part: frame_00002.png of the
    // first run must not linger next to a 2-frame run.
    std::vector<std::string> want = expected_files(2);
    want.push_back("notes.txt");
    std::sort(want.begin(), want.end());
    CHECK(list_dir(tmp / "out") == want);
    CHECK(read_file(tmp / "out" / "notes.txt") == "mine\n");
    const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
    CHECK(j["frames"] == 2);
    CHECK(j["frames_written"] == 2);
    for (int i = 0; i < 2; ++i) {
        const Image img = load_png(tmp / "out" / frame_name(i));
        INFO(img.error);
        CHECK(img.ok());
    }
}

TEST_CASE("ranryu record without --out writes to out/SCENE in the working folder", "[cli][record]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--frames", "1"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    REQUIRE(fs::is_directory(tmp / "out" / "cli-small"));
    CHECK(list_dir(tmp / "out" / "cli-small") == expected_files(1));
    // The scene's own render size (64x48 in small.json) when --size is not given.
    const Image img = load_png(tmp / "out" / "cli-small" / frame_name(0));
    INFO(img.error);
    REQUIRE(img.ok());
    CHECK(img.width == 64);
    CHECK(img.height == 48);
}

TEST_CASE("ranryu record --solver pbf runs a bundled scene: the scene's substeps, every PBF pass timed, no guard", "[cli][record][pbf]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--solver", "pbf", "--shading", "particles", "--size",
                                             "64x48", "--frames", "3", "--out", tmp.str("out")});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("wrote 3 frames (64x48)"));
    CHECK_THAT(r.err, !Contains("GL error"));
    const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
    INFO(j.dump(2));
    CHECK(j["substeps_per_frame"] == 4);   // sph.pbf.substeps' default: fixed, whatever the flow does
    std::vector<std::string> names;
    for (const auto& p : j["passes"]) names.push_back(p.at("name").get<std::string>());
    for (const char* pass : {"pbf.predict", "pbf.lambda", "pbf.correct", "pbf.velocity", "pbf.viscosity"}) {
        INFO("pass " << pass);
        CHECK(std::find(names.begin(), names.end(), pass) != names.end());
    }
    CHECK(std::find(names.begin(), names.end(), "dfsph.density") == names.end());
}
