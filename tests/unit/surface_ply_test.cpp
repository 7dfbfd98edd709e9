// engine/surface/ply.*: a binary little-endian PLY written, then parsed back here (header and every
// value); the write is atomic (no .tmp left behind) and failures name the file.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "support/gl_fixture.h"   // ranryu::test::Random only; no context is made here
#include "surface/ply.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("ranryu_surface_ply_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::uint32_t le32(const unsigned char* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t(p[3]) << 24; }
float lef32(const unsigned char* p) {
    const std::uint32_t u = le32(p);
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

}  // namespace

TEST_CASE("PLY: a written mesh parses back, header and data", "[surface]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    ranryu::surface::IndexedMesh m;
    const std::size_t nv = 1 + rng.below(300), nt = rng.below(500);
    for (std::size_t i = 0; i < nv; ++i) {
        m.positions.emplace_back(rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10));
        m.normals.push_back(glm::normalize(glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), 1.0f)));
    }
    for (std::size_t i = 0; i < nt; ++i)
        m.triangles.emplace_back(rng.below(unsigned(nv)), rng.below(unsigned(nv)), rng.below(unsigned(nv)));
    const fs::path dir = scratch_dir("roundtrip"), path = dir / "mesh.ply";
    std::ofstream(path) << "an older file, replaced";
    ranryu::surface::write_ply(path, m);
    CHECK(!fs::exists(dir / "mesh.ply.tmp"));

    std::ifstream f(path, std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const std::string end = "end_header\n";
    const auto split = all.find(end);
    REQUIRE(split != std::string::npos);
    std::istringstream header(all.substr(0, split));
    std::vector<std::string> lines;
    for (std::string line; std::getline(header, line);)
        if (line.rfind("comment", 0) != 0) lines.push_back(line);
    const std::vector<std::string> expected{"ply", "format binary_little_endian 1.0",
                                            "element vertex " + std::to_string(nv), "property float x",
                                            "property float y", "property float z", "property float nx",
                                            "property float ny", "property float nz",
                                            "element face " + std::to_string(nt),
                                            "property list uchar int vertex_indices"};
    CHECK(lines == expected);

    const auto* p = reinterpret_cast<const unsigned char*>(all.data() + split + end.size());
    REQUIRE(all.size() - split - end.size() == nv * 24 + nt * 13);
    for (std::size_t i = 0; i < nv; ++i, p += 24)
        for (int a = 0; a < 3; ++a) {
            CHECK(lef32(p + 4 * a) == m.positions[i][a]);
            CHECK(lef32(p + 12 + 4 * a) == m.normals[i][a]);
        }
    for (std::size_t i = 0; i < nt; ++i, p += 13) {
        CHECK(p[0] == 3);
        for (int a = 0; a < 3; ++a) CHECK(le32(p + 1 + 4 * a) == m.triangles[i][a]);
    }
    fs::remove_all(dir);
}

TEST_CASE("PLY: failures are errors naming the file", "[surface]") {
    const fs::path dir = scratch_dir("errors");
    ranryu::surface::IndexedMesh m{{glm::vec3(0)}, {glm::vec3(0, 0, 1)}, {glm::uvec3(0, 0, 1)}};
    const fs::path bad_index = dir / "bad_index.ply";
    CHECK_THROWS_WITH(ranryu::surface::write_ply(bad_index, m), Catch::Contains(bad_index.string()) && Catch::Contains("vertex 1"));
    CHECK(!fs::exists(bad_index));
    const fs::path missing = dir / "no" / "such" / "folder" / "mesh.ply";
    m.triangles.clear();
    CHECK_THROWS_WITH(ranryu::surface::write_ply(missing, m), Catch::Contains(missing.string()));
    m.normals.clear();
    CHECK_THROWS_AS(ranryu::surface::write_ply(dir / "normals.ply", m), ranryu::Error);
    fs::remove_all(dir);
}
