// record --checkpoint / --resume (engine/frame/checkpoint.h) end to end: a record stopped by SIGTERM
// (a batch job's time limit) leaves a checkpoint beside its frames, and the record resumed from it
// writes the frames an uninterrupted run writes, byte for byte, into the same folder, keeping the
// earlier frames and run.json (with PBF, whose substeps a frame are fixed, and with DFSPH, which plans
// its substeps and iteration caps from the record of the frame plan_lag() frames back: sim/fluid.h); a
// video of the resumed frames; and each misuse gets one line and exit 2 before any work.
#include <catch2/catch.hpp>

#include <csignal>

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
            "--checkpoint no/such/folder/c.bin: cannot write");
    CHECK_FALSE(fs::exists(tmp / "o1"));
    refused({"profile", "--scene", scene, "--frames", "2", "--checkpoint", "."}, "is a folder");
    // Not a checkpoint; none there.
    write_file(tmp / "x.bin", "not a checkpoint at all");
    refused({"record", "--resume", "x.bin", "--frames", "2"}, "--resume x.bin: not a ranryu checkpoint");
    refused({"profile", "--resume", "none.bin", "--frames", "2"}, "--resume none.bin: no such file");
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
