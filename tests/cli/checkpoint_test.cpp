// record --checkpoint / --resume (engine/frame/checkpoint.h) end to end: a record stopped by SIGTERM
// (a batch job's time limit) leaves a checkpoint beside its frames, and the record resumed from it
// writes the frames an uninterrupted run writes, byte for byte, into the same folder, keeping the
// earlier frames and run.json (with PBF, whose substeps a frame are fixed, and with DFSPH, which plans
// its substeps and iteration caps from the record of the frame plan_lag() frames back: sim/fluid.h); a
// video of the resumed frames; and each misuse gets one line and exit 2 before any work.
#include <catch2/catch.hpp>

#include <csignal>
#include <cstring>
#include <limits>

#include <nlohmann/json.hpp>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

std::string frame_file(const char* prefix, std::uint64_t f, const char* ext) {
    char name[48];
    std::snprintf(name, sizeof name, "%s_%05llu.%s", prefix, static_cast<unsigned long long>(f), ext);
    return name;
}

}  // namespace

TEST_CASE("checkpoint: a record stopped by SIGTERM resumes to the frames of an uninterrupted run, byte for byte",
          "[cli][checkpoint]") {
    TempDir tmp;
    const fs::path out = tmp / "out", straight = tmp / "straight";
    const std::vector<std::string> common = {"--size", "64x48", "--shading", "particles", "--export-particles", "ply", "--quiet"};
    const std::string solver = GENERATE(as<std::string>{}, "pbf", "dfsph");
    INFO("--solver " << solver);
    const std::vector<std::string> scene = {"--scene", scene_file("jet-at-box.json").string(), "--solver", solver};
    auto with = [&](std::vector<std::string> args) {
        args.insert(args.end(), common.begin(), common.end());
        return args;
    };
    std::vector<std::string> first_run = {"record", "--frames", "1000000", "--out", out.string(), "--checkpoint", "c.bin"};
    first_run.insert(first_run.end(), scene.begin(), scene.end());
    Child child = start_ranryu(tmp.path(), with(first_run));
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(out / frame_file("particles", 2, "ply")) && std::chrono::steady_clock::now() < end)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    kill(child.pid, SIGTERM);
    const Result stopped = wait(child);
    INFO(stopped.describe());
    REQUIRE(stopped.exit_code == 130);
    CHECK_THAT(stopped.out, Contains("wrote the checkpoint c.bin (frame "));
    REQUIRE(fs::exists(tmp / "c.bin"));
    const nlohmann::json first = nlohmann::json::parse(read_file(out / "run.json"));
    const auto at = first["interrupted_at_frame"].get<std::uint64_t>();
    CHECK(first["checkpoint"]["frame"] == at);
    const std::string first_report = read_file(out / "run.json");

    // Resumed for three frames more, into the same folder.
    const Result resumed = run_ranryu(tmp.path(), with({"record", "--resume", "c.bin", "--frames", "3", "--out", out.string()}));
    INFO(resumed.describe());
    REQUIRE(resumed.exit_code == 0);
    CHECK_THAT(resumed.out, Contains(frame_file("run_from", at, "json")));
    CHECK(read_file(out / "run.json") == first_report);   // the first run's report is kept
    const nlohmann::json second = nlohmann::json::parse(read_file(out / frame_file("run_from", at, "json")));
    CHECK(second["resumed_from"]["frame"] == at);
    CHECK(second["frames_written"] == 3);

    // The same scene run without a stop, as far.
    std::vector<std::string> whole_run = {"record", "--frames", std::to_string(at + 3), "--out", straight.string()};
    whole_run.insert(whole_run.end(), scene.begin(), scene.end());
    const Result whole = run_ranryu(tmp.path(), with(whole_run));
    INFO(whole.describe());
    REQUIRE(whole.exit_code == 0);
    for (std::uint64_t f = 0; f < at + 3; ++f) {
        INFO("frame " << f << " of " << at + 3 << ", the stop at " << at);
        for (const auto& [prefix, ext] : {std::pair{"frame", "png"}, std::pair{"particles", "ply"}}) {
            const fs::path a = out / frame_file(prefix, f, ext), b = straight / frame_file(prefix, f, ext);
            REQUIRE(fs::exists(a));
            CHECK(read_file(a) == read_file(b));
        }
    }

    // Resuming again into the folder that now holds those frames would write over them: refused,
    // nothing touched.
    const auto before = list_dir(out);
    const Result again = run_ranryu(tmp.path(), with({"record", "--resume", "c.bin", "--frames", "3", "--out", out.string()}));
    CHECK(again.exit_code == 2);
    CHECK_THAT(again.err, Contains("already holds frames or reports from frame " + std::to_string(at)) && Contains("--force"));
    CHECK(list_dir(out) == before);
}

TEST_CASE("checkpoint: a resumed record makes a video of its own frames", "[cli][checkpoint][video]") {
    if (!on_path("ffmpeg")) {
        if (env_is("RANRYU_REQUIRE_FFMPEG", "1")) FAIL("ffmpeg is not on PATH, and RANRYU_REQUIRE_FFMPEG=1 requires the video tests");
        WARN("skipped: ffmpeg is not on PATH");
        return;
    }
    TempDir tmp;
    const std::string scene = scene_file("small.json").string();
    const Result a = run_ranryu(tmp.path(), {"record", "--scene", scene, "--frames", "3", "--size", "64x48", "--out", "out",
                                             "--video", "a.mp4", "--checkpoint", "c.bin", "--quiet"});
    INFO(a.describe());
    REQUIRE(a.exit_code == 0);
    // Its frames are numbered from 3: the video's writer must take them from there (it waited for a
    // frame 0 that never came).
    const Result b = run_ranryu(tmp.path(), {"record", "--resume", "c.bin", "--frames", "2", "--size", "64x48", "--out", "out",
                                             "--video", "b.mp4", "--quiet"});
    INFO(b.describe());
    REQUIRE(b.exit_code == 0);
    CHECK_THAT(b.out, Contains("wrote the video b.mp4 (2 frames"));
    const nlohmann::json run = nlohmann::json::parse(read_file(tmp / "out" / "run_from_00003.json"));
    CHECK(run["video"]["frames"] == 2);
    CHECK(fs::exists(tmp / "out" / "frame_00004.png"));
}

TEST_CASE("checkpoint: misuse is one line and exit 2 before any work", "[cli][checkpoint][bad-input]") {
    TempDir tmp;
    const std::string scene = scene_file("small.json").string();
    auto refused = [&](const std::vector<std::string>& args, const std::string& says) {
        const Result r = run_ranryu(tmp.path(), args);
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        CHECK(r.err_lines().size() == 1);
        CHECK_THAT(r.err, Contains(says));
    };
    // An unwritable checkpoint is found before the run (no output folder made).
    refused({"record", "--scene", scene, "--frames", "2", "--out", "o1", "--checkpoint", "no/such/folder/c.bin"},
            "--checkpoint no/such/folder/c.bin: its folder no/such/folder does not exist");
    CHECK_FALSE(fs::exists(tmp / "o1"));
    refused({"profile", "--scene", scene, "--frames", "2", "--checkpoint", "."}, "is a folder");
    // Not a checkpoint; none there.
    write_file(tmp / "x.bin", "not a checkpoint at all");
    refused({"record", "--resume", "x.bin", "--frames", "2"}, "--resume x.bin: not a ranryu checkpoint");
    refused({"profile", "--resume", "none.bin", "--frames", "2"}, "--resume none.bin: no such file");
    fs::create_directory(tmp / "folder.bin");
    refused({"profile", "--resume", "folder.bin", "--frames", "2"}, "--resume folder.bin: is a folder");
    // A real one, with options that would contradict its scene.
    const Result made = run_ranryu(tmp.path(), {"profile", "--scene", scene, "--frames", "1", "--warmup", "0", "--size", "32x32",
                                                "--checkpoint", "c.bin", "--quiet"});
    INFO(made.describe());
    REQUIRE(made.exit_code == 0);
    refused({"profile", "--resume", "c.bin", "--scene", scene, "--frames", "1"}, "drop --scene");
    refused({"profile", "--resume", "c.bin", "--spacing", "0.05", "--frames", "1"}, "drop --spacing");
    refused({"record", "--resume", "c.bin", "--solver", "pbf", "--frames", "1"}, "drop --solver");
    // The earlier run's records are not written over.
    write_file(tmp / "records.csv", "frame,time\n");
    refused({"profile", "--resume", "c.bin", "--frames", "1", "--records", "records.csv"}, "--records records.csv: exists");
    CHECK(read_file(tmp / "records.csv") == "frame,time\n");
}

namespace {

// A checkpoint's parts (engine/frame/checkpoint.cpp: "RANRYUCP", the format, the header's length, the
// JSON header, the entries' bytes), to damage one and write it back whole.
struct CheckpointFile {
    std::string lead;   // magic and format
    nlohmann::json header;
    std::string body;
    explicit CheckpointFile(const std::string& bytes) {
        REQUIRE(bytes.size() > 20);
        lead = bytes.substr(0, 12);
        std::uint64_t length = 0;
        std::memcpy(&length, bytes.data() + 12, sizeof length);
        REQUIRE(20 + length <= bytes.size());
        header = nlohmann::json::parse(bytes.substr(20, length));
        body = bytes.substr(20 + length);
    }
    std::string bytes() const {
        const std::string text = header.dump();
        const std::uint64_t length = text.size();
        return lead + std::string(reinterpret_cast<const char*>(&length), sizeof length) + text + body;
    }
    std::size_t offset(const std::string& entry) const {   // of its bytes in `body`
        std::size_t at = 0;
        for (const auto& e : header["entries"]) {
            if (e["name"] == entry) return at;
            at += e["bytes"].get<std::size_t>();
        }
        FAIL("no entry " << entry);
        return 0;
    }
};

}  // namespace

TEST_CASE("checkpoint: a damaged file, or a folder of another run to resume into, is one line and exit 2 before any work",
          "[cli][checkpoint][bad-input]") {
    TempDir tmp;
    const std::vector<std::string> sph = {"--scene", "dam-break", "--spacing", "0.04"};   // 100 particles
    auto with = [](std::vector<std::string> args, const std::vector<std::string>& more) {
        args.insert(args.end(), more.begin(), more.end());
        return args;
    };
    const Result made = run_ranryu(tmp.path(), with({"record", "--frames", "2", "--size", "32x32", "--out", "run", "--checkpoint",
                                                     "c.bin", "--quiet"}, sph));
    INFO(made.describe());
    REQUIRE(made.exit_code == 0);
    const CheckpointFile good(read_file(tmp / "c.bin"));
    auto refused = [&](const std::string& name, const CheckpointFile& file, const std::string& says) {
        write_file(tmp / name, file.bytes());
        const Result r = run_ranryu(tmp.path(), {"profile", "--resume", name, "--frames", "1", "--warmup", "0", "--size", "32x32"});
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        CHECK(r.err_lines().size() == 1);
        CHECK_THAT(r.err, Contains("--resume " + name + ": " + says));
        CHECK(r.out.find("frame (GPU span)") == std::string::npos);   // no run
    };
    // The control: the file written back unchanged resumes.
    write_file(tmp / "same.bin", good.bytes());
    const Result same = run_ranryu(tmp.path(), {"profile", "--resume", "same.bin", "--frames", "1", "--warmup", "0", "--size", "32x32",
                                                "--quiet"});
    INFO(same.describe());
    CHECK(same.exit_code == 0);
    CheckpointFile count = good;
    count.header["particles"] = good.header["particles"].get<std::uint64_t>() + 7;
    refused("count.bin", count, "its header says 107 particles, and its scene has 100");
    CheckpointFile frame = good;
    frame.header["frame"] = -5;
    refused("frame.bin", frame, "malformed header: \"frame\" is not a whole number >= 0");
    CheckpointFile time = good;
    time.header["time"] = -1.0;
    refused("time.bin", time, "malformed header: \"time\" is not a finite time >= 0");
    CheckpointFile nan = good;
    const float bad = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(nan.body.data() + nan.offset("fluid.velocities") + 16 * 3 + 4, &bad, sizeof bad);   // particle 3's v.y
    refused("nan.bin", nan, "entry fluid.velocities holds a non-finite value (element 3)");

    // Resumed into the folder of another scene's run: refused, that run untouched.
    const Result other = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--frames", "1", "--size",
                                                 "32x32", "--out", "other", "--quiet"});
    INFO(other.describe());
    REQUIRE(other.exit_code == 0);
    const std::vector<std::string> before = list_dir(tmp / "other");
    const std::string report = read_file(tmp / "other" / "run.json");
    const Result into = run_ranryu(tmp.path(), {"record", "--resume", "c.bin", "--frames", "1", "--size", "32x32", "--out", "other", "--force"});
    INFO(into.describe());
    CHECK(into.exit_code == 2);
    CHECK(into.err_lines().size() == 1);
    CHECK_THAT(into.err, Contains("--out other: holds a run of scene cli-small"));
    CHECK(list_dir(tmp / "other") == before);
    CHECK(read_file(tmp / "other" / "run.json") == report);
    // And into its own run's folder it goes on.
    const Result own = run_ranryu(tmp.path(), {"record", "--resume", "c.bin", "--frames", "1", "--size", "32x32", "--out", "run", "--quiet"});
    INFO(own.describe());
    CHECK(own.exit_code == 0);
}

TEST_CASE("checkpoint: a run that goes unstable writes none, and says so", "[cli][checkpoint][guard]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene_file("unstable.json").string(), "--frames", "40", "--out",
                                             "out", "--shading", "particles", "--size", "32x32", "--checkpoint", "c.bin", "--quiet"});
    INFO(r.describe());
    CHECK(r.exit_code == 3);
    CHECK_FALSE(fs::exists(tmp / "c.bin"));
    CHECK_FALSE(fs::exists(tmp / "c.bin.tmp"));
    const nlohmann::json run = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
    CHECK(run["checkpoint"]["file"].is_null());
    CHECK_THAT(run["checkpoint"]["not_written"].get<std::string>(), Contains("unstable"));
}
