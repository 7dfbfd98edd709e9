#pragma once
// Exporting the SPH particles of every frame as particles_NNNNN.ply or .vtp (record/particle_files.h)
// beside the PNGs, without stalling the frame: record::MeshExporter's scheme for fixed-size data.
//
// capture() copies the particle buffers on the GPU (glCopyBufferSubData, pass "particle-readback")
// into the next slot of a ring of GL_STREAM_READ buffers and fences it; a later capture() finds the
// fence signalled, reads the copies into a preallocated CPU frame (sized once: the particle count
// does not change) and hands it to the writer thread through record::GatedWriter, which writes the
// file only once the frame is validated (frames after an instability never reach disk).
// Back-pressure as in record::Recorder: the render thread waits only when the whole ring is still in
// flight or every CPU frame is queued. Memory: each CPU frame and ring slot holds 16 B per particle
// for each of positions, velocities, densities and ê, and 4 B for the levels, of those present.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "record/particle_files.h"
#include "record/readback_queue.h"

namespace ranryu::frame { class Pipeline; }

namespace ranryu::record {

// The GPU buffers of one frame's particles, as capture() copies them. Null: not exported.
struct ParticleBuffers {
    const gl::Buffer* positions = nullptr;    // vec4[count]
    const gl::Buffer* velocities = nullptr;   // vec4[count]
    const gl::Buffer* densities = nullptr;    // vec4[count]: (ρ, p, ...), SPH only
    const gl::Buffer* levels = nullptr;       // uint[count]: L | E << 8, sub-particles only
    const gl::Buffer* energies = nullptr;     // vec4[count]: (û, ê), turbulence only
};
// A pipeline's particles after its simulate(): the fluid's (or the ballistic particles') positions and
// velocities, and the densities, sub-particle levels and wavelet energies of those it has.
ParticleBuffers particle_buffers(const frame::Pipeline& p);

class ParticleExporter {
public:
    // `count` particles; `shape`: which buffers every capture() passes (those non-null are written).
    ParticleExporter(profile::GpuTimer& timer, std::filesystem::path dir, ParticleFormat format, std::size_t count,
                     const ParticleBuffers& shape, bool gated, std::function<void()> pump = {}, int ring = 3);
    ~ParticleExporter();
    ParticleExporter(const ParticleExporter&) = delete;
    ParticleExporter& operator=(const ParticleExporter&) = delete;

    // Pass "particle-readback": queues the copies of `b` as frame number frames_captured(). Call after
    // the frame's simulation; `b` must hold exactly the buffers the constructor named.
    // Numbers the first capture `frame` (the files' names and the frames validate_through() and
    // discard_from() name): a run resumed from a checkpoint (frame/checkpoint.h). Before any capture.
    void start_at(std::uint64_t frame) { queue_.start_at(frame); }
    void capture(const ParticleBuffers& b);
    void validate_through(std::uint64_t frame);
    void discard_from(std::uint64_t frame);
    // Waits for every queued copy and file of validated frames, drops the rest. Throws ranryu::Error
    // if a file failed to write.
    void finish();

    std::uint64_t frames_captured() const { return queue_.captured(); }
    std::uint64_t frames_written() const { return queue_.writer().written(); }
    std::vector<std::string> fields() const;   // particle_fields() of this exporter

private:
    struct Arrays {   // one frame: GPU copies (ring) or CPU copies (writer), the absent ones empty
        gl::Buffer positions, velocities, densities, levels, energies;
    };
    struct Frame {
        std::uint64_t frame = 0;
        std::vector<glm::vec4> positions, velocities, densities, energies;
        std::vector<std::uint32_t> levels;
    };
    using Slot = ReadbackQueue<Arrays>::Slot;   // tag: the frame
    void retire(Slot& s);
    void write(std::size_t buffer);   // the writer thread's job: one file

    profile::GpuTimer& timer_;
    profile::PassId pass_;
    std::filesystem::path dir_;
    ParticleFormat format_;
    std::size_t count_;
    bool density_, level_, energy_;
    std::vector<Frame> buffers_;   // preallocated CPU frames, named by the writer's indices
    std::vector<char> scratch_;    // the writer thread's file bytes, reused
    ReadbackQueue<Arrays> queue_;  // last: its threads stop before the frames they write go
};

}  // namespace ranryu::record
