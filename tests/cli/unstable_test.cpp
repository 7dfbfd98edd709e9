// A simulation that goes unstable is stopped cleanly: exit code 3, one line naming the frame, step,
// simulated time and criterion, and record keeps every frame before it and writes none after.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "run_helper.h"

using namespace ranryu::test;

TEST_CASE("record of a scene that goes unstable exits 3 and keeps exactly the frames before it", "[cli][guard]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene_file("unstable.json").string(), "--frames", "40",
                                             "--out", "out", "--shading", "particles"});
    INFO(r.err);
    REQUIRE(r.exit_code == 3);
    CHECK_THAT(r.err, Catch::Contains("simulation unstable at frame") && Catch::Contains("step") &&
                          Catch::Contains("t = ") && Catch::Contains("particle"));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);

    const auto run = nlohmann::json::parse(read_file(tmp.path() / "out" / "run.json"));
    REQUIRE(run.contains("instability"));
    const auto bad = run["instability"]["frame"].get<std::uint64_t>();
    CHECK(bad < 40);
    // Frames 0 .. bad-1 are on disk; the unstable frame and everything after it are not.
    std::vector<std::string> pngs;
    for (const std::string& f : list_dir(tmp.path() / "out"))
        if (f.ends_with(".png")) pngs.push_back(f);
    CHECK(pngs.size() == bad);
    CHECK(run["frames_written"].get<std::uint64_t>() == bad);
    for (std::uint64_t f = 0; f < bad; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05llu.png", static_cast<unsigned long long>(f));
        CHECK(std::find(pngs.begin(), pngs.end(), name) != pngs.end());
    }
}
