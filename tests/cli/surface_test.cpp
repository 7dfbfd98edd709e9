// The liquid surface end to end: `--shading` picks how SPH liquid is drawn; the surface modes build
// the level set and marching cubes each frame (their passes appear in the timing table), particles
// builds neither; a bad mode, or a surface for a ballistic scene, is bad input (exit 2).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image.h"
#include "run_helper.h"
#include "shared/bindings.h"
#include "surface/mesh.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

const std::vector<std::string> kSurfacePasses = {"surface.anisotropy", "surface.bounds", "level-set.splat", "level-set",
                                                 "mc.classify", "mc.compact", "mc.emit", "draw-surface"};

// The pass names of the timing table on stdout (first word of each row after the "pass" header).
std::vector<std::string> table_passes(const std::string& out) {
    std::vector<std::string> names;
    bool in_table = false;
    for (const std::string& line : Result::split_lines(out)) {
        if (line.starts_with("pass ")) {
            in_table = true;
            continue;
        }
        if (in_table && !line.empty()) names.push_back(line.substr(0, line.find(' ')));
    }
    return names;
}
bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

// Reads a binary PLY as surface/ply.h writes it: vertices (x y z nx ny nz floats) and triangle faces
// (uchar 3, int indices), as a triangle soup in face order. Fails the test on any other layout.
std::vector<ranryu::gpu::MeshVertex> read_ply_soup(const fs::path& path, std::size_t* vertex_count) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    std::string line;
    std::size_t nv = 0, nf = 0;
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream w(line);
        std::string a, b;
        w >> a >> b;
        if (a == "element" && b == "vertex") w >> nv;
        if (a == "element" && b == "face") w >> nf;
    }
    REQUIRE(line == "end_header");
    std::vector<float> v(nv * 6);
    in.read(reinterpret_cast<char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
    std::vector<ranryu::gpu::MeshVertex> soup;
    for (std::size_t f = 0; f < nf; ++f) {
        unsigned char n = 0;
        std::int32_t idx[3];
        in.read(reinterpret_cast<char*>(&n), 1);
        REQUIRE(n == 3);
        in.read(reinterpret_cast<char*>(idx), sizeof idx);
        for (int k = 0; k < 3; ++k) {
            REQUIRE(std::size_t(idx[k]) < nv);
            const float* p = &v[std::size_t(idx[k]) * 6];
            soup.push_back({glm::vec4(p[0], p[1], p[2], 1.0f), glm::vec4(p[3], p[4], p[5], 0.0f)});
        }
    }
    REQUIRE(in.good());
    REQUIRE(in.peek() == std::char_traits<char>::eof());
    *vertex_count = nv;
    return soup;
}

}  // namespace

TEST_CASE("record --export-mesh writes a watertight PLY per frame holding every vertex of the MeshState") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--spacing", "0.04", "--frames", "2",
                                             "--size", "32x24", "--export-mesh", "--out", "out"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK(has(table_passes(r.out), "mesh-readback"));
    std::ifstream run_json(tmp / "out/run.json");
    const auto run = nlohmann::json::parse(run_json);
    REQUIRE(run.at("meshes").size() == 2);
    for (int f = 0; f < 2; ++f) {
        const auto& m = run.at("meshes")[std::size_t(f)];
        CHECK(m.at("frame") == f);
        CHECK(m.at("vertices_cut") == false);
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.ply", f);
        INFO(name);
        std::size_t nv = 0;
        const auto soup = read_ply_soup(tmp / ("out/" + std::string(name)), &nv);
        CHECK(nv == m.at("vertices").get<std::size_t>());
        CHECK(soup.size() == nv);
        CHECK(nv > 300);
        const auto topo = ranryu::surface::topology(ranryu::surface::weld(soup));
        INFO("edges not in two faces " << topo.boundary_or_nonmanifold_edges << ", misoriented " << topo.misoriented_edges
                                       << ", degenerate " << topo.degenerate_faces);
        CHECK(topo.watertight());
    }
    // A run drawn as particles has no surface to export: refused before anything is written.
    const Result p = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--shading", "particles", "--export-mesh",
                                             "--out", "parts"});
    INFO(p.describe());
    CHECK(p.exit_code == 2);
    CHECK_THAT(p.err, Contains("--export-mesh"));
    CHECK(!fs::exists(tmp / "parts"));
}

TEST_CASE("record --shading fresnel draws the SPH surface into non-uniform frames") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--spacing", "0.04", "--frames", "2",
                                             "--shading", "fresnel", "--size", "64x48", "--out", "out"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const auto passes = table_passes(r.out);
    for (const std::string& p : kSurfacePasses) {
        INFO("pass " << p);
        CHECK(has(passes, p));
    }
    CHECK(!has(passes, "draw-particles"));
    for (int f = 0; f < 2; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", f);
        const Image img = load_png(tmp / ("out/" + std::string(name)));
        INFO(name << ": " << img.error);
        REQUIRE(img.ok());
        CHECK(img.width == 64);
        CHECK(img.height == 48);
        CHECK(img.distinct_colours() > 20);
        CHECK(img.luma_stddev() > 5.0);
    }
}

TEST_CASE("profile names the surface passes in the surface modes and not in particles mode, and the water mode's own passes") {
    TempDir tmp;
    for (const std::string mode : {"water", "fresnel", "particles"}) {
        const Result r = run_ranryu(tmp.path(), {"profile", "--scene", "dam-break", "--spacing", "0.04", "--frames", "2",
                                                 "--warmup", "0", "--size", "32x24", "--shading", mode});
        INFO(mode << "\n" << r.describe());
        REQUIRE(r.exit_code == 0);
        const auto passes = table_passes(r.out);
        for (const std::string& p : kSurfacePasses) {
            INFO("pass " << p);
            CHECK(has(passes, p) == (mode != "particles"));
        }
        CHECK(has(passes, "draw-particles") == (mode == "particles"));
        for (const std::string p : {"shadow-map", "draw-sky", "draw-walls", "liquid-thickness", "compose"}) {
            INFO("pass " << p);
            CHECK(has(passes, p) == (mode == "water"));
        }
    }
}

TEST_CASE("profile draws the water mode's opaque scene once with the scene cache and every frame without, and refuses bad option values") {
    TempDir tmp;
    const std::vector<std::string> args = {"profile", "--scene", "dam-break", "--spacing", "0.04", "--frames", "4", "--warmup", "0",
                                           "--size", "32x24", "--shading", "water", "--json", "profile.json"};
    for (const std::string cache : {"1", "0"}) {
        RunOptions opt;
        // Without the cache, the draws' raster as well: both rasters of (R14) run through the command.
        opt.set_env = {{"RANRYU_WATER_CACHE", cache},
                       {"RANRYU_WATER_THICKNESS_DIVISOR", cache == "1" ? "2" : "1"},
                       {"RANRYU_WATER_RASTER", cache == "1" ? "compute" : "draw"}};
        const Result r = run_ranryu(tmp.path(), args, opt);
        INFO("RANRYU_WATER_CACHE=" << cache << "\n" << r.describe());
        REQUIRE(r.exit_code == 0);
        std::ifstream in(tmp / "profile.json");
        const auto report = nlohmann::json::parse(in);
        auto calls = [&](const std::string& pass) {
            for (const auto& p : report.at("passes"))
                if (p.at("name") == pass) return p.at("calls_per_frame").get<double>();
            return 0.0;
        };
        // The camera stays: with the cache the opaque scene is drawn in the first frame alone.
        for (const std::string p : {"clear", "draw-sky", "draw-floor", "draw-walls", "draw-tank"}) {
            INFO("pass " << p);
            CHECK(calls(p) == Approx(cache == "1" ? 0.25 : 1.0));
        }
        for (const std::string p : {"shadow-map", "liquid-thickness", "compose", "draw-surface"}) {
            INFO("pass " << p);
            CHECK(calls(p) == Approx(1.0));
        }
    }
    for (const auto& [name, value] : std::vector<std::pair<std::string, std::string>>{
             {"RANRYU_WATER_CACHE", "yes"}, {"RANRYU_WATER_THICKNESS_DIVISOR", "8"}, {"RANRYU_WATER_RASTER", "hardware"},
             {"RANRYU_PARTICLE_RASTER", "points"}, {"RANRYU_DFSPH_CAP", "1.5,0.5"}}) {
        RunOptions opt;
        opt.set_env = {{name, value}};
        const Result r = run_ranryu(tmp.path(), args, opt);
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains(name + "=" + value));
    }
}

TEST_CASE("record and profile take a shading mode of water, fresnel, phong, gouraud or particles, and a surface only for SPH scenes") {
    TempDir tmp;
    Result r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--shading", "bogus", "--out", "out"});
    {
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains("--shading bogus"));
        CHECK_THAT(r.err, Contains("water, fresnel, phong, gouraud, particles"));
        CHECK(!fs::exists(tmp / "out"));
    }
    r = run_ranryu(tmp.path(), {"profile", "--scene", "falling-block", "--frames", "1", "--warmup", "0", "--size", "32x24",
                                "--shading", "phong"});
    {
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains("--shading phong"));
        CHECK_THAT(r.err, Contains("ballistic"));
    }
    for (const std::string mode : {"water", "phong", "gouraud"}) {
        r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--spacing", "0.04", "--frames", "1", "--shading",
                                    mode, "--size", "32x24", "--out", "out-" + mode});
        INFO(mode << "\n" << r.describe());
        CHECK(r.exit_code == 0);
        const Image img = load_png(tmp / ("out-" + mode + "/frame_00000.png"));
        CHECK(img.ok());
        CHECK(img.distinct_colours() > 10);
    }
}

TEST_CASE("A pool at rest: its surface normals within 1° rms of vertical, from the exported mesh") {
    // A pool 10 particles deep in a 0.4 x 0.3 x 0.2 m tank (Δx = 0.02 m, 2000 particles), one frame
    // simulated from rest, its mesh exported. The top's vertices (within Δx of the fill height H, more
    // than 4Δx from the walls, where the surface turns down) must face up: the rms angle of their
    // normals (−∇φ, docs/SURFACE.md (S8)) from +y within 1° with anisotropic kernels (the default),
    // and below the spherical kernels' (whose bumps over the particles tilt the normals). With Akinci's
    // boundary term, whose first frame rearranges the lattice beside the walls (docs/DFSPH.md): with
    // DFSPH's default boundary rows the pool holds its lattice, and both kernels read 0.03° rms.
    TempDir tmp;
    const float dx = 0.02f, H = 0.2f;
    double rms[2] = {0.0, 0.0};
    for (const bool anisotropic : {true, false}) {
        const std::string name = anisotropic ? "aniso" : "iso";
        write_file(tmp / (name + ".json"), std::string(R"({"name": "pool", "model": "sph", "tank": {"min": [0, 0, 0], "max": [0.4, 0.3, 0.2]},
            "particles": {"spacing": 0.02, "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.2, 0.2]}]},
            "sph": {"viscosity": 1e-3, "boundary_rows": false}, "surface": {"anisotropic": )") + (anisotropic ? "true" : "false") + "}}");
        const Result r = run_ranryu(tmp.path(), {"record", "--scene", name + ".json", "--frames", "1", "--size", "32x24",
                                                 "--export-mesh", "--out", name});
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        std::size_t nv = 0;
        const auto soup = read_ply_soup(tmp / (name + "/frame_00000.ply"), &nv);
        double sum2 = 0.0, worst = 0.0;
        std::size_t count = 0;
        for (const auto& v : soup) {
            const glm::vec3 p(v.position);
            if (std::abs(p.y - H) > dx || p.x < 4 * dx || p.x > 0.4f - 4 * dx || p.z < 4 * dx || p.z > 0.2f - 4 * dx) continue;
            const double deg = glm::degrees(std::acos(std::clamp(double(v.normal.y), -1.0, 1.0)));
            sum2 += deg * deg;
            worst = std::max(worst, deg);
            ++count;
        }
        rms[anisotropic] = count ? std::sqrt(sum2 / double(count)) : 0.0;
        INFO(name << ": " << count << " top vertices; normals off vertical by " << rms[anisotropic] << "° rms, " << worst
                  << "° at worst");
        REQUIRE(count > 100);
        if (anisotropic) CHECK(rms[1] < 1.0);
    }
    INFO("rms " << rms[1] << "° anisotropic, " << rms[0] << "° spherical");
    CHECK(rms[1] < rms[0]);
}
