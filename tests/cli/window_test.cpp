// ranryu run: the GLFW window path, under a virtual X server (xvfb-run, Mesa GLX).
//
// Without a window in the build (no GLFW at configure time) or without xvfb-run on PATH these cases
// are skipped with a warning, unless RANRYU_REQUIRE_XVFB=1 (as CI sets it), where they fail.
#include <catch2/catch.hpp>

#include <regex>

#include <glm/glm.hpp>

#include "image.h"
#include "run_helper.h"
#include "support/particle_reader.h"

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


// The screenshots a run reported, in order: its lines "wrote PATH (WxH, frame F, panel at X,Y size
// WxH)" or "wrote PATH (WxH, frame F, no panel)".
struct Shot {
    std::string file;
    std::uint64_t frame = 0;
    bool panel = false;
    int x = 0, y = 0, width = 0, height = 0;
};
std::vector<Shot> shots_of(const Result& r) {
    static const std::regex line(R"(wrote (\S+shot_\d{5}\.png) \(\d+x\d+, frame (\d+), (?:panel at (\d+),(\d+) size (\d+)x(\d+)|no panel)\))");
    std::vector<Shot> shots;
    for (const std::string& l : r.out_lines()) {
        std::smatch m;
        if (!std::regex_match(l, m, line)) continue;
        Shot s{m[1], std::stoull(m[2]), m[3].matched};
        if (s.panel) s.x = std::stoi(m[3]), s.y = std::stoi(m[4]), s.width = std::stoi(m[5]), s.height = std::stoi(m[6]);
        shots.push_back(s);
    }
    return shots;
}

// Pixels whose RGB differ between two images of one size, and the box around them.
struct Diff {
    std::size_t pixels = 0;
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
};
Diff diff(const Image& a, const Image& b) {
    Diff d;
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const std::size_t i = (std::size_t(y) * std::size_t(a.width) + std::size_t(x)) * 4;
            if (a.rgba[i] == b.rgba[i] && a.rgba[i + 1] == b.rgba[i + 1] && a.rgba[i + 2] == b.rgba[i + 2]) continue;
            ++d.pixels;
            d.x0 = std::min(d.x0, x), d.y0 = std::min(d.y0, y), d.x1 = std::max(d.x1, x), d.y1 = std::max(d.y1, y);
        }
    return d;
}

// An earlier file at `rel` in tmp (its folders made), which a run must leave as it is; returns its text.
std::string plant_earlier(const TempDir& tmp, const std::string& rel) {
    const std::string text = "an earlier file, not to be lost: " + rel + "\n";
    fs::create_directories((tmp / rel).parent_path());
    write_file(tmp / rel, text);
    return text;
}

// `ranryu run ARGS --script script.txt` (the script's text written into tmp) under xvfb-run with a
// 640x480x24 screen; it must succeed without a GL error. Returns the run and the screenshots it took.
struct ScriptRun {
    Result result;
    std::vector<Shot> shots;
    std::vector<Image> images;   // of the shots, in order
};
ScriptRun run_script(const TempDir& tmp, const std::string& script, std::vector<std::string> args) {
    write_file(tmp / "script.txt", script);
    std::vector<std::string> argv = {"xvfb-run", "-a", "-s", "-screen 0 640x480x24", kBin, "run", "--script", "script.txt"};
    argv.insert(argv.end(), args.begin(), args.end());
    ScriptRun sr;
    sr.result = run(argv, {.cwd = tmp.path(), .timeout = std::chrono::seconds(120), .unset_env = {}, .set_env = {}});
    INFO(sr.result.describe());
    REQUIRE(sr.result.exit_code == 0);
    CHECK_THAT(sr.result.err, !Contains("GL error"));
    sr.shots = shots_of(sr.result);
    for (const Shot& shot : sr.shots) sr.images.push_back(load_png(tmp / shot.file));
    return sr;
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

// The demo's controls, driven by --script under Xvfb. The ballistic falling-block scene: cheap on
// llvmpipe, and deterministic, so a restart gives the same picture bit for bit.

TEST_CASE("ranryu run --script: pause freezes the picture and a single step moves it on", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const ScriptRun r = run_script(tmp,
                                   "0 key h        # no panel: its fps would change between shots\n"
                                   "1 key f12\n"
                                   "2 key f12      # running: moved on\n"
                                   "3 key space    # pause before frame 3\n"
                                   "5 key f12\n"
                                   "8 key f12      # paused: the same picture\n"
                                   "9 key n        # one frame simulates\n"
                                   "11 key f12\n"
                                   "12 key f12     # and it holds again\n"
                                   "13 key escape\n",
                                   {"--scene", "falling-block", "--size", "320x240"});
    INFO(r.result.describe());
    REQUIRE(r.shots.size() == 6);
    CHECK(r.shots[0].file == "screenshots/shot_00000.png");
    CHECK(r.shots[5].file == "screenshots/shot_00005.png");
    CHECK(r.shots[0].frame == 1);
    CHECK(r.shots[2].frame == 5);
    CHECK(r.shots[4].frame == 11);
    CHECK_FALSE(r.shots[0].panel);
    const std::vector<Image>& img = r.images;
    CHECK(img[0].distinct_colours() >= 16);
    CHECK(diff(img[0], img[1]).pixels > 50);   // running: it moved
    CHECK(diff(img[2], img[3]).pixels == 0);   // paused: two screenshots equal
    CHECK(diff(img[3], img[4]).pixels > 50);   // the single step moved it on
    CHECK(diff(img[4], img[5]).pixels == 0);   // and it held again
}

TEST_CASE("ranryu run --script: reset brings back the first frame", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const ScriptRun r = run_script(tmp,
                                   "0 key h\n"
                                   "0 key f12\n"
                                   "6 key f12\n"
                                   "7 key r        # restart: frame 7 is the scene's first frame again\n"
                                   "7 key f12\n"
                                   "8 panel reset  # the panel's button does the same, paused or not\n"
                                   "8 panel pause on\n"
                                   "8 key f12\n"
                                   "10 panel quit\n",
                                   {"--scene", "falling-block", "--size", "320x240"});
    INFO(r.result.describe());
    REQUIRE(r.shots.size() == 4);
    const std::vector<Image>& img = r.images;
    CHECK(diff(img[0], img[1]).pixels > 50);   // frame 6 is not frame 0
    CHECK(diff(img[0], img[2]).pixels == 0);   // after r: frame 0 again
    CHECK(diff(img[0], img[3]).pixels == 0);   // after the panel's reset, paused: frame 0 again
}

TEST_CASE("ranryu run --script: the overlay changes the picture in the panel's region only", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const ScriptRun r = run_script(tmp,
                                   "3 key space\n"
                                   "4 key f12      # with the panel\n"
                                   "5 key h\n"
                                   "6 key f12      # without\n"
                                   "7 key h\n"
                                   "8 key escape\n",
                                   {"--scene", "falling-block", "--size", "640x480", "--shots", "out/shots"});
    INFO(r.result.describe());
    CHECK_THAT(r.result.out, Contains("overlay"));   // its own pass in the timing table
    REQUIRE(r.shots.size() == 2);
    REQUIRE(r.shots[0].panel);
    CHECK_FALSE(r.shots[1].panel);
    CHECK(r.shots[0].file == "out/shots/shot_00000.png");
    const Shot& p = r.shots[0];
    INFO("panel at " << p.x << "," << p.y << " size " << p.width << "x" << p.height);
    CHECK(p.width >= 100);
    CHECK(p.height >= 100);
    CHECK(p.x + p.width <= 640);
    CHECK(p.y + p.height <= 480);
    const Diff d = diff(r.images[0], r.images[1]);
    INFO("differing pixels " << d.pixels << " in " << d.x0 << "," << d.y0 << " - " << d.x1 << "," << d.y1);
    CHECK(d.pixels > std::size_t(p.width * p.height / 4));   // the panel is drawn
    CHECK(d.x0 >= p.x - 1);
    CHECK(d.y0 >= p.y - 1);
    CHECK(d.x1 <= p.x + p.width);
    CHECK(d.y1 <= p.y + p.height);
}

TEST_CASE("ranryu run: a screenshot never replaces an earlier one", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const std::string earlier = plant_earlier(tmp, "screenshots/shot_00000.png");
    const ScriptRun r = run_script(tmp, "1 key f12\n1 panel screenshot\n3 key escape\n",
                                   {"--scene", "falling-block", "--size", "160x120"});
    INFO(r.result.describe());
    REQUIRE(r.shots.size() == 2);
    CHECK(r.shots[0].file == "screenshots/shot_00001.png");   // one a frame: the key's at 1, the panel's at 2
    CHECK(r.shots[0].frame == 1);
    CHECK(r.shots[1].file == "screenshots/shot_00002.png");
    CHECK(r.shots[1].frame == 2);
    CHECK(read_file(tmp / "screenshots/shot_00000.png") == earlier);
    CHECK(r.images[1].ok());
}

TEST_CASE("ranryu run --script: the panel's scene, shading and solver restart an SPH scene", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const ScriptRun r = run_script(tmp,
                                   "2 panel shading particles\n"
                                   "4 key m            # particles -> water (the cycle wraps)\n"
                                   "5 panel solver wcsph\n"
                                   "6 key f12\n"
                                   "7 panel scene falling-block\n"
                                   "8 key m            # ballistic: particles only, a note in the panel\n"
                                   "9 drag 40 -10\n"
                                   "9 wheel 1\n"
                                   "10 key escape\n",
                                   {"--scene", "drop", "--spacing", "0.05", "--size", "320x240"});
    INFO(r.result.describe());
    REQUIRE(r.shots.size() == 1);
    CHECK(r.shots[0].panel);
    CHECK(r.images[0].ok());
    // Each change restarted the scene, before the frame of its line.
    // The drop ships with PBF (its sph.why).
    CHECK_THAT(r.result.out, Contains("restart at frame 2: drop, pbf, particles\n"));
    CHECK_THAT(r.result.out, Contains("restart at frame 4: drop, pbf, water\n"));
    CHECK_THAT(r.result.out, Contains("restart at frame 5: drop, wcsph, water\n"));
    CHECK_THAT(r.result.out, Contains("restart at frame 7: falling-block, ballistic, particles\n"));
    CHECK_THAT(r.result.out, !Contains("restart at frame 8"));   // m: nothing to change
    CHECK_THAT(r.result.out, Contains("scene falling-block"));   // the last scene's report
}

// "simulation (dfsph): 4.0 substeps/frame" in a run's report, or -1.
double substeps_per_frame(const std::string& out) {
    static const std::regex line(R"(simulation \((?:dfsph|wcsph)\): ([0-9.]+) substeps/frame)");
    std::smatch m;
    return std::regex_search(out, m, line) ? std::stod(m[1]) : -1.0;
}

TEST_CASE("ranryu run --script: viscosity, the time-step factor and the turbulence act live", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    // DFSPH: the drop ships with PBF, whose fixed step has no Courant number to change.
    const std::vector<std::string> drop = {"--scene", "drop", "--solver", "dfsph", "--spacing", "0.05", "--size", "160x120"};
    TempDir plain_dir, live_dir, turbulence_dir;
    const ScriptRun plain = run_script(plain_dir, "12 key escape\n", drop);
    const ScriptRun live = run_script(live_dir, "0 panel cfl 0.1\n0 panel viscosity 0.001\n12 key escape\n", drop);
    const double before = substeps_per_frame(plain.result.out), after = substeps_per_frame(live.result.out);
    INFO(plain.result.describe() << "\n" << live.result.describe());
    REQUIRE(before > 0.0);
    CHECK(after > before * 1.4);   // a quarter of the Courant number: more, smaller substeps
    CHECK_THAT(live.result.out, !Contains("restart"));

    // The dam break sets DFSPH's own Courant number (sph.dfsph_cfl 0.5, docs/DFSPH.md (D8)): the panel's
    // cfl is that one, not sph.cfl, which DFSPH does not read there.
    // 512 particles for 0.4 s, the column falling at 1-3 m/s: the CFL step, not the largest, binds.
    const std::vector<std::string> dam = {"--scene", "dam-break", "--solver", "dfsph", "--spacing", "0.025", "--size", "160x120"};
    TempDir dam_plain_dir, dam_live_dir;
    const ScriptRun dam_plain = run_script(dam_plain_dir, "24 key escape\n", dam);
    const ScriptRun dam_live = run_script(dam_live_dir, "0 panel cfl 0.1\n24 key escape\n", dam);
    const double dam_before = substeps_per_frame(dam_plain.result.out), dam_after = substeps_per_frame(dam_live.result.out);
    INFO(dam_plain.result.describe() << "\n" << dam_live.result.describe());
    REQUIRE(dam_before > 0.0);
    CHECK(dam_after > dam_before * 1.4);   // a fifth of the Courant number in force

    // The drop has no turbulence force: turning it on restarts the scene with it; off and on again,
    // and a new amplitude, are live.
    const ScriptRun t = run_script(turbulence_dir, "0 key t\n3 panel amplitude 20\n4 key t\n6 panel turbulence on\n8 key escape\n", drop);
    INFO(t.result.describe());
    CHECK_THAT(t.result.out, Contains("restart at frame 0: drop, dfsph, water\n"));
    CHECK_THAT(t.result.out, !Contains("restart at frame 4"));
    CHECK_THAT(t.result.out, !Contains("restart at frame 6"));
    CHECK_THAT(t.result.out, Contains("turbulence-force"));
}

// "paddle at X Y Z radius R m" in a run's output: the paddle's last centre, or nothing.
struct PaddleLine {
    bool found = false;
    glm::dvec3 at{0.0};
    double radius = 0.0;
};
PaddleLine paddle_of(const std::string& out) {
    static const std::regex line(R"(paddle at (\S+) (\S+) (\S+) radius (\S+) m)");
    std::smatch m;
    PaddleLine p;
    if (!std::regex_search(out, m, line)) return p;
    p = {true, glm::dvec3(std::stod(m[1]), std::stod(m[2]), std::stod(m[3])), std::stod(m[4])};
    return p;
}
std::vector<glm::dvec3> positions_of(const ranryu::test::PointCloud& pc) {
    std::vector<glm::dvec3> x(pc.count);
    for (std::size_t i = 0; i < pc.count; ++i) x[i] = {pc.values.at("x")[i], pc.values.at("y")[i], pc.values.at("z")[i]};
    return x;
}

TEST_CASE("ranryu run --script: a dragged paddle moves the liquid near its path and no particle ends inside it", "[cli][window][script][paddle]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    // A resting pool 0.2 m deep, the camera looking along -z: the paddle (radius 3 dx = 0.075 m)
    // appears above the middle of the pool, a drag of 25 pixels down takes it 0.15 m down into the
    // liquid (6 mm a pixel at 1 m, 120 pixels high), and one of 17 pixels left 0.1 m towards -x. The
    // same run without the paddle is the liquid it moved.
    const std::vector<std::string> args = {"--scene", scene_file("paddle-pool.json").string(), "--size", "160x120",
                                           "--shading", "particles", "--save-particles", "last.ply"};
    TempDir with_dir, without_dir;
    const ScriptRun with = run_script(with_dir, "0 key h\n0 panel paddle on\n1 paddle 0 25\n20 paddle -17 0\n44 key f12\n45 key escape\n", args);
    const ScriptRun without = run_script(without_dir, "45 key escape\n", args);
    INFO(with.result.describe() << "\n" << without.result.describe());
    const PaddleLine p = paddle_of(with.result.out);
    REQUIRE(p.found);
    CHECK_FALSE(paddle_of(without.result.out).found);
    INFO("paddle at " << p.at.x << ", " << p.at.y << ", " << p.at.z << ", radius " << p.radius);
    CHECK(p.radius == Approx(0.075));
    CHECK(p.at.y < 0.2 - 0.5 * p.radius);   // it went down into the liquid
    CHECK(p.at.x < 0.15);                   // and along it

    const std::vector<glm::dvec3> x = positions_of(ranryu::test::read_ply(with_dir / "last.ply"));
    const std::vector<glm::dvec3> y = positions_of(ranryu::test::read_ply(without_dir / "last.ply"));
    REQUIRE(x.size() == y.size());
    double nearest = 1e30;
    for (const glm::dvec3& q : x) nearest = std::min(nearest, glm::length(q - p.at));
    std::size_t displaced = 0;   // without the paddle, liquid where it ends
    for (const glm::dvec3& q : y) displaced += glm::length(q - p.at) < p.radius;
    INFO("nearest centre " << nearest << " m from the paddle's; " << displaced << " particles there without it");
    CHECK(nearest >= p.radius * (1.0 - 1e-5));   // the projection's bound, in the %.6f printed
    // The ball holds (4/3) pi R^3 / dx^3 = 113 lattice sites; more than half of it lies in the pool.
    CHECK(displaced >= 40);
    REQUIRE(with.shots.size() == 1);
    CHECK(with.images[0].ok());
}

TEST_CASE("ranryu run --script: F9 records takes through the asynchronous writer, never over an earlier one", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const std::string earlier = plant_earlier(tmp, "recordings/take_000/frame_00000.png");
    const ScriptRun r = run_script(tmp, "0 key h\n1 key f9\n4 key f9\n6 panel record on\n8 panel record off\n9 key escape\n",
                                   {"--scene", "falling-block", "--size", "96x64"});
    INFO(r.result.describe());
    CHECK_THAT(r.result.out, Contains("recording into recordings/take_001\n"));
    CHECK_THAT(r.result.out, Contains("recorded 3 frames into recordings/take_001\n"));
    CHECK_THAT(r.result.out, Contains("recorded 2 frames into recordings/take_002\n"));
    CHECK(read_file(tmp / "recordings/take_000/frame_00000.png") == earlier);
    CHECK(list_dir(tmp / "recordings/take_001") == std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png"});
    CHECK(list_dir(tmp / "recordings/take_002") == std::vector<std::string>{"frame_00000.png", "frame_00001.png"});
    const Image a = load_png(tmp / "recordings/take_001/frame_00000.png"), b = load_png(tmp / "recordings/take_001/frame_00002.png");
    CHECK(a.width == 96);
    CHECK(a.height == 64);
    CHECK(diff(a, b).pixels > 20);   // frames 1 and 3 of a falling block
}

// "particles: N at spacing DX m" lines, in order.
std::vector<std::pair<std::size_t, double>> particle_lines(const std::string& out) {
    static const std::regex line(R"(particles: (\d+) at spacing (\S+) m)");
    std::vector<std::pair<std::size_t, double>> v;
    for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator(); ++it)
        v.emplace_back(std::stoull((*it)[1]), std::stod((*it)[2]));
    return v;
}

TEST_CASE("ranryu run --script: the panel's spacing rebuilds the scene at that resolution", "[cli][window][script]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    TempDir tmp;
    const ScriptRun r = run_script(tmp, "2 panel spacing 0.04\n3 panel spacing 0.0001   # too many particles: a note, no restart\n4 key escape\n",
                                   {"--scene", "drop", "--spacing", "0.05", "--size", "96x64", "--shading", "particles"});
    INFO(r.result.describe());
    const auto lines = particle_lines(r.result.out);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0].second == Approx(0.05));
    CHECK(lines[1].second == Approx(0.04));
    // The drop's blocks on lattices of the spacing: (0.05 / 0.04)^3 = 1.95 times the particles, give
    // or take a lattice row of each block.
    const double ratio = double(lines[1].first) / double(lines[0].first);
    INFO("particles " << lines[0].first << " -> " << lines[1].first);
    CHECK(ratio > 1.5);
    CHECK(ratio < 2.5);
    CHECK_THAT(r.result.out, Contains("restart at frame 2: drop, pbf, particles\n"));
    CHECK_THAT(r.result.out, !Contains("restart at frame 3"));
}

// "particles: A active of budget B" at the end of a run.
std::pair<std::size_t, std::size_t> active_of(const std::string& out) {
    static const std::regex line(R"(particles: (\d+) active of budget (\d+))");
    std::smatch m;
    if (!std::regex_search(out, m, line)) return {0, 0};
    return {std::stoull(m[1]), std::stoull(m[2])};
}

TEST_CASE("ranryu run --script: the emitter raises the live count up to the budget and not beyond", "[cli][window][script][emitter]") {
    if (!window_available(/*need_xvfb=*/true)) return;
    // The pool's 16 x 8 x 16 particles and a budget 10 beyond them: its emitter's sheet is 2 x 2, so
    // 3 frames of pouring spend the budget (4, 4, 2) and the rest pour nothing.
    const std::vector<std::string> args = {"--scene", scene_file("paddle-pool.json").string(), "--size", "96x64", "--shading",
                                           "particles", "--budget", "2058", "--save-particles", "last.ply"};
    TempDir full_dir, one_dir;
    const ScriptRun full = run_script(full_dir, "0 key e\n8 key escape\n", args);
    const ScriptRun one = run_script(one_dir, "0 panel emitter on\n1 panel emitter off\n8 key escape\n", args);
    INFO(full.result.describe() << "\n" << one.result.describe());
    const auto lines = particle_lines(full.result.out);
    REQUIRE(lines.size() == 1);
    REQUIRE(lines[0].first == 2048);
    CHECK_THAT(full.result.out, Contains("particle budget: 2058"));
    CHECK(active_of(full.result.out) == std::pair<std::size_t, std::size_t>(2058, 2058));
    CHECK(active_of(one.result.out) == std::pair<std::size_t, std::size_t>(2052, 2058));
    // The saved particles agree: every one of the budget is there, those not poured parked below the
    // tank (1 m under its floor), the poured ones in it.
    for (const auto& [dir, poured] : {std::pair<const TempDir*, std::size_t>{&full_dir, 10}, {&one_dir, 4}}) {
        const std::vector<glm::dvec3> x = positions_of(ranryu::test::read_ply(*dir / "last.ply"));
        REQUIRE(x.size() == 2058);
        std::size_t parked = 0;
        for (const glm::dvec3& q : x) parked += q.y < -0.5;
        CHECK(parked == 10 - poured);
    }
}
