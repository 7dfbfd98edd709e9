// ranryu run: the GLFW window path, under a virtual X server (xvfb-run, Mesa GLX).
//
// Without a window in the build (no GLFW at configure time) or without xvfb-run on PATH these cases
// are skipped with a warning, unless RANRYU_REQUIRE_XVFB=1 (as CI sets it), where they fail.
#include <catch2/catch.hpp>

#include "image.h"
#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

constexpr bool kHaveWindow = RANRYU_HAVE_WINDOW;

// True if the case can run; otherwise WARNs (skip) or FAILs (RANRYU_REQUIRE_XVFB=1) and returns false.
bool window_available(bool need_xvfb) {
    std::string why;
    if (!kHaveWindow) why = "this build has no window (GLFW was not found at configure time)";
    else if (need_xvfb && !on_path("xvfb-run")) why = "xvfb-run is not on PATH";
    if (why.empty()) return true;
    if (env_is("RANRYU_REQUIRE_XVFB", "1")) {
        FAIL(why << ", and RANRYU_REQUIRE_XVFB=1 requires the window tests");
        return false;
    }
    WARN("skipped: " << why << " (set RANRYU_REQUIRE_XVFB=1 to make this a failure)");
    return false;
}

}  // namespace

TEST_CASE("ranryu run under Xvfb saves a --screenshot that is not blank", "[cli][window]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const std::string shot = tmp.str("shot.png");
    const Result r = run({"xvfb-run", "-a", "-s", "-screen 0 640x480x24", kBin, "run", "--frames", "5", "--size", "64x48",
                          "--screenshot", shot},
                         {.cwd = tmp.path(), .timeout = std::chrono::seconds(60), .unset_env = {}, .set_env = {}});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("wrote " + shot));
    CHECK_THAT(r.out, Contains("present"));       // the window's own pass is timed too
    CHECK_THAT(r.out, Contains("overlay"));       // and the panel's
    CHECK_THAT(r.err, !Contains("GL error"));    // Debug builds report every GL error on stderr
    REQUIRE(fs::exists(shot));

    const Image img = load_png(shot);
    INFO("screenshot: " << img.error << ", " << img.width << "x" << img.height << ", " << img.distinct_colours()
                        << " colours, luma sd " << img.luma_stddev());
    REQUIRE(img.ok());
    // No window manager under Xvfb: the framebuffer is the size asked for.
    CHECK(img.width == 64);
    CHECK(img.height == 48);
    CHECK(img.distinct_colours() >= 16);   // a rendered scene, not a single colour
    CHECK(img.luma_stddev() > 2.0);
    // The PNG is renamed into place: no temporary file is left.
    CHECK(list_dir(tmp.path()) == std::vector<std::string>{"shot.png"});
}

TEST_CASE("ranryu run --screenshot onto an existing file is refused without touching it", "[cli][window][bad-input]") {
    if (!window_available(/*need_xvfb=*/false)) return;
    TempDir tmp;
    const std::string shot = tmp.str("shot.png");
    const std::string earlier = "an earlier screenshot, not to be lost\n";
    write_file(shot, earlier);
    const auto mtime = fs::last_write_time(shot);

    // No display at all: the refusal must come before any window is opened.
    const RunOptions no_display{.cwd = tmp.path(), .timeout = std::chrono::seconds(60), .unset_env = {"DISPLAY", "WAYLAND_DISPLAY"}, .set_env = {}};
    const Result r = run_ranryu(tmp.path(), {"run", "--frames", "5", "--size", "64x48", "--screenshot", shot}, no_display);
    INFO(r.describe());
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    CHECK(r.err_lines().size() == 1);
    CHECK_THAT(r.err, Contains("--screenshot " + shot));
    CHECK(read_file(shot) == earlier);
    CHECK(fs::last_write_time(shot) == mtime);
    CHECK(list_dir(tmp.path()) == std::vector<std::string>{"shot.png"});

    SECTION("and so is a screenshot into a folder that does not exist") {
        const std::string missing = tmp.str("no-such-folder/shot.png");
        const Result m = run_ranryu(tmp.path(), {"run", "--frames", "5", "--size", "64x48", "--screenshot", missing}, no_display);
        INFO(m.describe());
        CHECK(m.exit_code == 2);
        CHECK(m.err_lines().size() == 1);
        CHECK_THAT(m.err, Contains("--screenshot " + missing));
        CHECK_FALSE(fs::exists(tmp / "no-such-folder"));
    }
}
