// ranryu record --export-particles ply|vtp (engine/record/particle_export.h): one file per frame,
// particles_00000.EXT, read back by the tests' own reader of the PLY and VTK specifications
// (tests/support/particle_reader.h): the count and fields run.json names, a well-nested VTP with
// NumberOfPoints and its arrays. That the values are the GPU's is tests/gl/particle_export_test.cpp's.
// Also scripts/gpu/fast-particles.py, which reads such files on the GPU host, against the same reader.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_helper.h"
#include "scene/scene.h"
#include "support/particle_reader.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

// The bundled turbulent jet at 320 particles (turbulence and sub-particles on), drawn as particles.
Result record_jet(const TempDir& tmp, const std::string& format, int frames, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"record", "--scene", "turbulent-jet", "--spacing", "0.04", "--size", "64x48",
                                     "--shading", "particles", "--frames", std::to_string(frames), "--out", "out",
                                     "--export-particles", format, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_ranryu(tmp.path(), args);
}

std::string particle_file(int i, const std::string& ext) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "particles_%05d.%s", i, ext.c_str());
    return buf;
}

void check_sane(const PointCloud& pc) {
    for (std::size_t i = 0; i < pc.count; ++i) {
        INFO("particle " << i);
        for (const char* axis : {"x", "y", "z"}) CHECK(std::isfinite(pc.values.at(axis)[i]));
        // Inside the jet's tank (1.2 x 0.5 x 0.2 m, closed), with a density near water's.
        CHECK(pc.values.at("x")[i] >= 0.0);
        CHECK(pc.values.at("x")[i] <= 1.2);
        CHECK(pc.values.at("y")[i] >= 0.0);
        CHECK(pc.values.at("y")[i] <= 0.5);
        CHECK(pc.values.at("density")[i] > 100.0);
        CHECK(pc.values.at("density")[i] < 1500.0);
        CHECK(pc.values.at("level")[i] >= 0.0);
        CHECK(pc.values.at("energy")[i] >= 0.0);
    }
}

}  // namespace

TEST_CASE("ranryu record --export-particles writes a PLY or VTP per frame that a reader of the format reads",
          "[cli][record][particles]") {
    TempDir tmp;
    const int frames = 3;
    for (const std::string format : {"ply", "vtp"}) {
        INFO("format " << format);
        const Result r = record_jet(tmp, format, frames, {"--force"});
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        CHECK_THAT(r.out, Contains("wrote the particles of 3 frames as particles_*." + format));
        const nlohmann::json run = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
        INFO(run.dump(2));
        const nlohmann::json& p = run.at("particle_files");
        CHECK(p["format"] == format);
        CHECK(p["pattern"] == "particles_%05d." + format);
        CHECK(p["frames_written"] == frames);
        CHECK(p["order"] == "gpu-cell-order");
        CHECK(p["count"] == run["particles"]);   // the run's particle count
        const auto fields = p["fields"].get<std::vector<std::string>>();
        CHECK(fields == std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "density", "pressure", "level", "energy"});
        for (int i = 0; i < frames; ++i) {
            const fs::path file = tmp / "out" / particle_file(i, format);
            INFO(file.string());
            REQUIRE(fs::exists(file));
            const PointCloud pc = format == "ply" ? read_ply(file) : read_vtp(file);
            CHECK(pc.count == p["count"].get<std::size_t>());
            CHECK(pc.count == 320);
            std::vector<std::string> names = pc.names, want = fields;
            std::sort(names.begin(), names.end());
            std::sort(want.begin(), want.end());
            CHECK(names == want);
            check_sane(pc);
            if (format == "vtp") {
                // The XML: VTKFile > PolyData > Piece > PointData, Points, Verts, then the data.
                CHECK(pc.elements.front() == "VTKFile");
                for (const char* e : {"PolyData", "Piece", "PointData", "Points", "Verts", "DataArray"})
                    CHECK(std::find(pc.elements.begin(), pc.elements.end(), e) != pc.elements.end());
                CHECK(pc.piece.at("NumberOfPoints") == "320");
                CHECK(pc.connectivity.size() == 320);
            }
        }
        CHECK(!fs::exists(tmp / "out" / particle_file(frames, format)));
    }
}

TEST_CASE("ranryu record --export-particles of a ballistic scene writes positions and velocities only",
          "[cli][record][particles]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--frames", "2",
                                             "--out", "out", "--export-particles", "ply", "--quiet"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const PointCloud pc = read_ply(tmp / "out" / "particles_00001.ply");
    CHECK(pc.count == 144);
    CHECK(pc.names == std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz"});
}

TEST_CASE("ranryu record --export-particles: an unknown format is exit 2 naming it; an earlier run's files are "
          "refused without --force", "[cli][record][particles]") {
    TempDir tmp;
    const Result bad = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--out", "out",
                                               "--export-particles", "xyz"});
    INFO(bad.describe());
    CHECK(bad.exit_code == 2);
    REQUIRE(bad.err_lines().size() == 1);
    CHECK_THAT(bad.err, Contains("--export-particles xyz") && Contains("ply") && Contains("vtp"));
    CHECK(list_dir(tmp.path()).empty());
    // --no-png with nothing else to write would record nothing.
    const Result nothing = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--out", "out", "--no-png"});
    INFO(nothing.describe());
    CHECK(nothing.exit_code == 2);
    CHECK_THAT(nothing.err, Contains("--no-png"));
    CHECK(list_dir(tmp.path()).empty());

    const std::vector<std::string> args = {"record", "--scene", scene_file("small.json").string(), "--frames", "2",
                                           "--out", "out", "--export-particles", "vtp", "--no-png", "--quiet"};
    REQUIRE(run_ranryu(tmp.path(), args).exit_code == 0);
    CHECK(list_dir(tmp / "out") == std::vector<std::string>{"particles_00000.vtp", "particles_00001.vtp", "run.json"});
    const Result again = run_ranryu(tmp.path(), args);
    INFO(again.describe());
    CHECK(again.exit_code == 2);
    CHECK_THAT(again.err, Contains("--force"));
    std::vector<std::string> forced = args;
    forced.push_back("--force");
    const Result f = run_ranryu(tmp.path(), forced);
    INFO(f.describe());
    CHECK(f.exit_code == 0);
    CHECK_THAT(f.out, Contains("removed 3 files"));
}

TEST_CASE("scripts/gpu/fast-particles.py: the fastest particles of an exported frame, their distances to the walls, "
          "and the count past a speed, as the tests' own reader of the file computes them", "[cli][particles][script]") {
    // The turbulent jet at 320 particles (its PLY carries the uchar level, so the script's mixed-type
    // path runs), frame 1; the script against the same numbers from read_ply() (particle_reader.h).
    TempDir tmp;
    const Result r = record_jet(tmp, "ply", 2, {"--no-png"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const fs::path file = tmp / "out" / "particles_00001.ply";
    const PointCloud pc = read_ply(file);
    REQUIRE(pc.count > 100);
    const ranryu::scene::Scene scene = ranryu::scene::load("turbulent-jet");
    const glm::dvec3 lo(scene.tank_min), hi(scene.tank_max);
    const double dx = 0.04, past = 1.0;
    auto at = [&](const char* name, std::size_t i) { return pc.values.at(name)[i]; };
    std::vector<double> speed(pc.count);
    for (std::size_t i = 0; i < pc.count; ++i)
        speed[i] = std::sqrt(at("vx", i) * at("vx", i) + at("vy", i) * at("vy", i) + at("vz", i) * at("vz", i));
    const double fastest = *std::max_element(speed.begin(), speed.end());
    // The five walls the script measures (no lid): -x, +x, floor, -z, +z, in spacings.
    auto walls = [&](std::size_t i) {
        return std::vector<double>{(at("x", i) - lo.x) / dx, (hi.x - at("x", i)) / dx, (at("y", i) - lo.y) / dx,
                                   (at("z", i) - lo.z) / dx, (hi.z - at("z", i)) / dx};
    };
    std::size_t fast = 0;
    std::vector<std::size_t> near(4, 0);
    for (std::size_t i = 0; i < pc.count; ++i) {
        if (speed[i] <= past) continue;
        ++fast;
        const std::vector<double> w = walls(i);
        near[std::min<std::size_t>(3, std::count_if(w.begin(), w.end(), [](double d) { return d < 2.0; }))] += 1;
    }
    REQUIRE(fast > 0);   // the jet moves at 2.5 m/s

    char tank[160];
    std::snprintf(tank, sizeof tank, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    const Result s = run({"/usr/bin/python3", (source_dir() / "scripts" / "gpu" / "fast-particles.py").string(), "--spacing", "0.04",
                          "--tank", tank, "--top", "3", "--speed", "1.0", file.string()});
    INFO(s.describe());
    REQUIRE(s.exit_code == 0);
    const std::vector<std::string> out = s.out_lines();
    REQUIRE(out.size() == 6);   // the file's line, the header, three particles, the count
    char head[64];
    std::snprintf(head, sizeof head, "%zu particles, fastest %.3f m/s", pc.count, fastest);
    CHECK_THAT(out[0], Contains(head));
    // The first listed particle: the fastest (another of equal speed may stand first), its walls.
    std::istringstream row(out[2]);
    std::size_t index = 0;
    double listed = 0.0;
    row >> index >> listed;
    REQUIRE(index < pc.count);
    CHECK(speed[index] == Approx(fastest).margin(1e-6));
    CHECK(listed == Approx(fastest).margin(5e-4));
    std::string token;
    for (int k = 0; k < 4; ++k) row >> token;   // vx vy vz |
    REQUIRE(token == "|");
    for (double want : walls(index)) {
        double got = 0.0;
        row >> got;
        CHECK(got == Approx(want).margin(0.051));   // printed with one decimal
    }
    char count[160];
    std::snprintf(count, sizeof count, "past 1.0 m/s: %zu particles; within 2 spacings of 0/1/2/3 walls: %zu/%zu/%zu/%zu;", fast,
                  near[0], near[1], near[2], near[3]);
    CHECK_THAT(out[5], Contains(count));
}

TEST_CASE("scripts/gpu/scene-at.py: the spacing for about N particles, and with --dividing one that divides every block", "[cli]") {
    // The tank at rest's block is 0.3 x 0.25 x 0.1 m (media/scenes/hydrostatic.json): (V / N)^(1/3) for
    // about 1M particles is 1.96 mm, which leaves the far walls 0.56 and 0.52 spacings from the lattice;
    // the dividing spacings are 0.05 m / k, and the nearest is 0.05 / 26 (1,054,560 particles).
    TempDir tmp;
    const std::string script = (source_dir() / "scripts" / "gpu" / "scene-at.py").string();
    RunOptions in_source;
    in_source.cwd = source_dir();
    auto spacing_of = [&](std::vector<std::string> args) {
        args.insert(args.begin(), {"/usr/bin/python3", script});
        const Result r = run(args, in_source);
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        REQUIRE(r.out_lines().size() == 1);
        return std::stod(r.out_lines()[0]);
    };
    const std::string out = tmp.str("tank.json");
    CHECK(spacing_of({"hydrostatic", out, "1000000", "sph.solver=dfsph"}) == Approx(std::cbrt(0.3 * 0.25 * 0.1 / 1e6)).margin(5e-6));
    const nlohmann::json written = nlohmann::json::parse(read_file(out));
    CHECK(written["sph"]["solver"] == "dfsph");
    for (const double n : {1e6, 2.5e5, 3e4}) {
        INFO(n << " particles asked");
        const double dx = spacing_of({"--dividing", "hydrostatic", out, std::to_string(int(n))});
        double count = 1.0;
        for (const double extent : {0.3, 0.25, 0.1}) {
            const double cells = extent / dx;
            CHECK(std::abs(cells - std::round(cells)) < 1e-6);   // whole: the far wall half a spacing away
            count *= std::round(cells);
        }
        // The nearest of the dividing spacings: the next finer or coarser one is farther from n.
        const double k = std::round(0.05 / dx);
        auto particles = [](double kk) { return 60.0 * kk * kk * kk; };   // 6k x 5k x 2k
        CHECK(count == Approx(particles(k)));
        CHECK(std::abs(std::cbrt(count) - std::cbrt(n)) <= std::abs(std::cbrt(particles(k + 1)) - std::cbrt(n)));
        CHECK(std::abs(std::cbrt(count) - std::cbrt(n)) <= std::abs(std::cbrt(particles(k - 1)) - std::cbrt(n)));
    }
    // A block whose extents share no divisor near the spacing asked (0.1000007 m: their gcd is 1 um):
    // one line naming the scene and the divisor, exit non-zero, where it printed a spacing of 1 um.
    RunOptions quiet = in_source;
    const Result bad = run({"/usr/bin/python3", script, "--dividing", "hydrostatic", out, "1000000",
                            R"(particles.blocks=[{"min": [0, 0, 0], "max": [0.3, 0.25, 0.1000007]}])"},
                           quiet);
    INFO(bad.describe());
    CHECK(bad.exit_code != 0);
    CHECK(bad.out.empty());
    CHECK_THAT(bad.err, Contains("hydrostatic") && Contains("no divisor near 0.00196 m") && Contains("1e-06 m"));
}
