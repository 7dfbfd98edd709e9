#pragma once
// Shared by the SPH GL tests: a scene parsed from inline JSON and its sim::Sph (which samples the
// boundary and computes psi at construction), on the fixture's context, with the helpers the tests
// use to run whole frames and read fields back.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/sph.h"
#include "support/gl_fixture.h"

namespace ranryu::test {

struct SphRig {
    bool ready = (context(), true);
    scene::Scene scene;
    profile::GpuTimer timer{4, 4096};
    sim::Sph sph;
    SphRig(const std::string& json, const std::string& origin) : SphRig(scene::parse(json, origin)) {}
    explicit SphRig(scene::Scene s) : scene(std::move(s)), sph(shader::FileSource::embedded(), timer, scene) {}

    // One whole frame: begin, the substeps the model asks for, end; then collect arrived records.
    void frame(std::uint64_t index) {
        timer.begin_frame();
        sph.begin_frame(index);
        for (int s = 0; s < sph.substeps_this_frame(); ++s) sph.substep();
        sph.end_frame();
        timer.end_frame();
        sph.poll_records();
    }
    // Waits for the outstanding timings and records.
    void finish() {
        timer.drain();
        sph.drain_records();
    }
    std::vector<glm::vec4> read(const gl::Buffer& b) const { return b.read<glm::vec4>(sph.count()); }
    gpu::StepState step() const { return sph.step_state().read<gpu::StepState>(1)[0]; }
};

}  // namespace ranryu::test
