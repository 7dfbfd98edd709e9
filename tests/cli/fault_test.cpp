// A GPU fault during `record` (engine/gl/faults.h): a GL error raised in a pass stops the run with
// exit 1 and a message naming the pass and the frame; the frames before it are whole and written,
// the faulting frame and those after are not, and run.json says what happened. The fault is
// injected with RANRYU_FAULT_AT_FRAME (engine/frame/pipeline.h): an invalid GL call in a pass of its
// own. --gl-debug turns on the check of glGetError after every pass, as a Debug build does by itself
// (a Release build, the GPU host's, leaves it out of the frame path: engine/gl/faults.h).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "image.h"
#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

TEST_CASE("fault: a GL error in a pass stops record with exit 1 naming the pass, and the frames before it are intact",
          "[cli][fault]") {
    // Every frame waits for its frame's end before it is written (its readback can finish before the
    // fault ends the frame), SPH frames for their guard's records too.
    const std::string scene = GENERATE(as<std::string>(), "small.json", "sph");
    INFO(scene);
    TempDir tmp;
    const fs::path out = tmp.path() / "out";
    std::vector<std::string> args = {"record", "--size", "64x48", "--frames", "10", "--out", out.string(), "--quiet", "--gl-debug"};
    if (scene == "sph") args.insert(args.end(), {"--scene", "dam-break", "--spacing", "0.05", "--shading", "particles"});
    else args.insert(args.end(), {"--scene", scene_file(scene).string()});
    RunOptions opt;
    opt.set_env = {{"RANRYU_FAULT_AT_FRAME", "5"}};
    const Result r = run_ranryu(tmp.path(), args, opt);
    INFO(r.out << r.err);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("GL_INVALID_OPERATION) in pass fault-injection, frame 5"));
    for (int f = 0; f < 5; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", f);
        REQUIRE(fs::exists(out / name));
        check_whole_png(out / name, 64, 48);
    }
    for (int f = 5; f < 10; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", f);
        CHECK_FALSE(fs::exists(out / name));
    }
    const auto run = nlohmann::json::parse(read_file(out / "run.json"));
    CHECK(run["fault"]["frame"] == 5);
    CHECK_THAT(run["fault"]["message"].get<std::string>(), Contains("fault-injection"));
    CHECK(run["interrupted"] == false);
    CHECK(run["frames_written"] == 5);
}

TEST_CASE("fault: RANRYU_FAULT_AT_FRAME that is not a frame number is bad input", "[cli][fault]") {
    TempDir tmp;
    RunOptions opt;
    opt.set_env = {{"RANRYU_FAULT_AT_FRAME", "soon"}};
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--frames", "2", "--out",
                                             (tmp.path() / "out").string(), "--quiet"},
                                opt);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("RANRYU_FAULT_AT_FRAME=soon"));
}
