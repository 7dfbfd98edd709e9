// record::ParticleExporter (engine/record/particle_export.h): the particle files of every frame, read
// back with a reader of the PLY and VTK specifications written apart from the writer
// (tests/support/particle_reader.h), hold exactly the GPU's buffers of that frame (each value a copy
// of a float or integer: no tolerance), in the GPU's order; and a frame after an instability is never
// written.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frame/pipeline.h"
#include "record/particle_export.h"
#include "record/recorder.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "support/gl_fixture.h"
#include "support/particle_reader.h"
#include "turbulence/force.h"

namespace fs = std::filesystem;
using ranryu::test::PointCloud;

namespace {

// A folder under /tmp for the files, removed with everything in it.
struct Folder {
    fs::path path;
    Folder() {
        std::string tmpl = "/tmp/ranryu-particles-XXXXXX";
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
        path = tmpl;
    }
    ~Folder() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

// What the GPU held at the end of one frame, read synchronously (a test may wait).
struct Snapshot {
    std::vector<glm::vec4> positions, velocities, densities, energies;
    std::vector<std::uint32_t> levels;
};

Snapshot snapshot(const ranryu::frame::Pipeline& p) {
    const std::size_t n = p.particle_count();
    const ranryu::record::ParticleBuffers b = ranryu::record::particle_buffers(p);
    Snapshot s;
    s.positions = b.positions->read<glm::vec4>(n);
    s.velocities = b.velocities->read<glm::vec4>(n);
    if (b.densities) s.densities = b.densities->read<glm::vec4>(n);
    if (b.energies) s.energies = b.energies->read<glm::vec4>(n);
    if (b.levels) s.levels = b.levels->read<std::uint32_t>(n);
    return s;
}

// Every value of the file equals the snapshot's, bit for bit as a float (or the level's integer).
void check_equal(const PointCloud& pc, const Snapshot& s, const std::string& file) {
    INFO(file);
    const std::size_t n = s.positions.size();
    REQUIRE(pc.count == n);
    const std::vector<std::string> want = {"x", "y", "z", "vx", "vy", "vz", "density", "pressure", "level", "energy"};
    std::vector<std::string> names = pc.names, sorted = want;   // a VTP's arrays stand in any order
    std::sort(names.begin(), names.end());
    std::sort(sorted.begin(), sorted.end());
    REQUIRE(names == sorted);
    if (file.ends_with("ply")) CHECK(pc.names == want);   // PLY: the documented order of the record
    std::size_t mismatches = 0;
    auto same = [&](const char* name, std::size_t i, double expected) {
        if (pc.values.at(name)[i] != expected && ++mismatches <= 5)
            FAIL_CHECK(name << "[" << i << "]: file " << pc.values.at(name)[i] << ", GPU " << expected);
    };
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < 3; ++a) {
            same(want[std::size_t(a)].c_str(), i, s.positions[i][a]);
            same(want[std::size_t(3 + a)].c_str(), i, s.velocities[i][a]);
        }
        same("density", i, s.densities[i].x);
        same("pressure", i, s.densities[i].y);
        same("level", i, double(s.levels[i] >> RANRYU_SUBPARTICLE_SPLIT_SHIFT));
        same("energy", i, s.energies[i].w);
    }
    CHECK(mismatches == 0);
}

// The bundled turbulent jet at 320 particles, its threshold low enough that particles split.
ranryu::scene::Scene jet() {
    ranryu::scene::Scene s = ranryu::scene::with_spacing(ranryu::scene::load("turbulent-jet"), 0.04f, "test");
    s.turbulence.subparticles.threshold = 1e-4f;
    return s;
}

}  // namespace

TEST_CASE("particle export: the PLY and VTP files of every frame hold exactly the GPU's buffers", "[record][particles]") {
    ranryu::test::context();
    const ranryu::scene::Scene scene = jet();
    const auto shaders = ranryu::shader::FileSource::embedded();
    ranryu::frame::Pipeline pipeline(scene, shaders, ranryu::frame::View{64, 48, std::nullopt, false});
    REQUIRE(pipeline.subparticles() != nullptr);
    REQUIRE(pipeline.simulation()->turbulence() != nullptr);
    const std::size_t n = pipeline.particle_count();
    REQUIRE(n == 320);

    Folder ply_dir, vtp_dir;
    using ranryu::record::ParticleExporter;
    using ranryu::record::ParticleFormat;
    // Gated, as record runs them: each frame written once the guard's record says it is sound.
    ParticleExporter ply(pipeline.timer(), ply_dir.path, ParticleFormat::ply, n, ranryu::record::particle_buffers(pipeline), true);
    ParticleExporter vtp(pipeline.timer(), vtp_dir.path, ParticleFormat::vtp, n, ranryu::record::particle_buffers(pipeline), true);
    const int frames = 5;   // more than the ring of 3 copies
    std::vector<Snapshot> gpu;
    for (int f = 0; f < frames; ++f) {
        pipeline.begin_frame();
        pipeline.simulate();
        ply.capture(ranryu::record::particle_buffers(pipeline));
        vtp.capture(ranryu::record::particle_buffers(pipeline));
        gpu.push_back(snapshot(pipeline));
        pipeline.end_frame();
        if (const auto sound = pipeline.poll()) {
            ply.validate_through(*sound);
            vtp.validate_through(*sound);
        }
    }
    pipeline.drain();
    REQUIRE(!pipeline.instability());
    const auto sound = pipeline.poll();
    REQUIRE(sound);
    CHECK(*sound == frames - 1);
    ply.validate_through(*sound);
    vtp.validate_through(*sound);
    ply.finish();
    vtp.finish();
    CHECK(ply.frames_written() == frames);
    CHECK(vtp.frames_written() == frames);
    ranryu::test::require_no_gl_errors();

    bool split = false, moved = false;
    for (int f = 0; f < frames; ++f) {
        const PointCloud a = ranryu::test::read_ply(ply_dir.path / ranryu::record::frame_name(std::uint64_t(f), "ply", "particles"));
        const PointCloud b = ranryu::test::read_vtp(vtp_dir.path / ranryu::record::frame_name(std::uint64_t(f), "vtp", "particles"));
        check_equal(a, gpu[std::size_t(f)], "frame " + std::to_string(f) + " ply");
        check_equal(b, gpu[std::size_t(f)], "frame " + std::to_string(f) + " vtp");
        CHECK(a.types.at("x") == "float");
        CHECK(a.types.at("level") == "uchar");
        CHECK(b.types.at("x") == "Float32");
        CHECK(b.types.at("level") == "UInt8");
        // Verts: one vertex a particle, so that ParaView draws them.
        REQUIRE(b.connectivity.size() == n);
        REQUIRE(b.offsets.size() == n);
        for (std::size_t i = 0; i < n; ++i) {
            CHECK(b.connectivity[i] == double(i));
            CHECK(b.offsets[i] == double(i + 1));
        }
        CHECK(b.piece.at("NumberOfVerts") == std::to_string(n));
        for (std::uint32_t l : gpu[std::size_t(f)].levels) split = split || (l >> RANRYU_SUBPARTICLE_SPLIT_SHIFT) > 0;
        if (f > 0) moved = moved || gpu[std::size_t(f)].positions != gpu[0].positions;
    }
    // Not a trivial comparison: the jet moves and some of its particles split.
    CHECK(split);
    CHECK(moved);
}

TEST_CASE("particle export: without turbulence only position, velocity, density and pressure; frames after an "
          "instability are not written", "[record][particles]") {
    ranryu::test::context();
    ranryu::scene::Scene scene = ranryu::scene::with_spacing(ranryu::scene::load("dam-break"), 0.08f, "test");
    REQUIRE(!scene.turbulence.enabled());
    const auto shaders = ranryu::shader::FileSource::embedded();
    ranryu::frame::Pipeline pipeline(scene, shaders, ranryu::frame::View{64, 48, std::nullopt, false});
    const std::size_t n = pipeline.particle_count();
    Folder dir;
    ranryu::record::ParticleExporter ply(pipeline.timer(), dir.path, ranryu::record::ParticleFormat::ply, n,
                                         ranryu::record::particle_buffers(pipeline), true);
    CHECK(ply.fields() == std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "density", "pressure"});
    std::vector<Snapshot> gpu;
    for (int f = 0; f < 4; ++f) {
        pipeline.begin_frame();
        pipeline.simulate();
        ply.capture(ranryu::record::particle_buffers(pipeline));
        gpu.push_back(snapshot(pipeline));
        pipeline.end_frame();
    }
    pipeline.drain();
    // As record does when the guard finds frame 2 unsound: 0 and 1 are written, 2 and 3 never.
    ply.validate_through(1);
    ply.discard_from(2);
    ply.finish();
    CHECK(ply.frames_written() == 2);
    CHECK(fs::exists(dir.path / "particles_00001.ply"));
    CHECK(!fs::exists(dir.path / "particles_00002.ply"));
    CHECK(!fs::exists(dir.path / "particles_00003.ply"));
    for (int f = 0; f < 2; ++f) {
        const PointCloud pc = ranryu::test::read_ply(dir.path / ranryu::record::frame_name(std::uint64_t(f), "ply", "particles"));
        REQUIRE(pc.count == n);
        CHECK(pc.names == std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "density", "pressure"});
        const Snapshot& s = gpu[std::size_t(f)];
        std::size_t mismatches = 0;
        for (std::size_t i = 0; i < n; ++i)
            mismatches += pc.values.at("x")[i] != s.positions[i].x || pc.values.at("vy")[i] != s.velocities[i].y ||
                          pc.values.at("density")[i] != s.densities[i].x || pc.values.at("pressure")[i] != s.densities[i].y;
        CHECK(mismatches == 0);
    }
}
