#pragma once
// Exporting the liquid surface as frame_NNNNN.ply beside the PNGs, without stalling the frame.
//
// capture() copies marching cubes' vertex buffer and MeshState on the GPU (glCopyBufferSubData, pass
// "mesh-readback") into the next slot of a ring of GL_STREAM_READ buffers, each sized by the mesh's
// capacity (max_vertices · 32 bytes, since the vertex count is known only on the GPU), and fences
// it. A later capture() finds the fence signalled, maps the MeshState and then just the first
// draw.x vertices, copies them into a reusable CPU buffer (its storage grows to the largest mesh
// seen, so after the first frames nothing is allocated) and hands it to a writer thread, which
// writes the PLY (surface::write_ply). Back-pressure as in record::Recorder: the render thread waits
// only when the whole ring is still in flight or every CPU buffer is queued.
//
// The file holds marching cubes' triangle soup as the GPU wrote it: one PLY vertex per mesh vertex
// (position and normal), faces (3i, 3i+1, 3i+2). Shared edge vertices are bit-identical, so
// surface::weld() rebuilds the indexed, watertight mesh (a reader's "merge by distance" with 0).
//
// Frames are written only once validated, through the same record::GatedWriter as record::Recorder.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "record/readback_queue.h"
#include "shared/bindings.h"

namespace ranryu::record {

// What one exported frame held, as its MeshState said.
struct MeshRecord {
    std::uint64_t frame = 0;
    std::uint32_t vertices = 0;   // MeshState.draw.x: vertices drawn and written
    bool cut = false;             // MeshState.totals.z: vertices past the capacity were dropped
    bool grid_too_big = false;    // MeshState.totals.w: the φ grid exceeded the capacity (empty mesh)
};

class MeshExporter {
public:
    // `max_vertices`: the capacity of the vertex buffers that capture() will copy from.
    MeshExporter(profile::GpuTimer& timer, std::filesystem::path dir, std::size_t max_vertices, bool gated,
                 std::function<void()> pump = {}, int ring = 3);
    ~MeshExporter();
    // Device memory the constructor allocates: its readback ring (frame/memory.h).
    static std::size_t bytes_for(std::size_t max_vertices, int ring = 3);
    MeshExporter(const MeshExporter&) = delete;
    MeshExporter& operator=(const MeshExporter&) = delete;

    // Pass "mesh-readback": queues the copy of `vertices` (gpu::MeshVertex[max_vertices]) and
    // `state` (gpu::MeshState) as frame number frames_captured(). Call after the mesh's passes.
    // Numbers the first capture `frame` (the files' names and the frames validate_through() and
    // discard_from() name): a run resumed from a checkpoint (frame/checkpoint.h). Before any capture.
    void start_at(std::uint64_t frame) { queue_.start_at(frame); }
    void capture(const gl::Buffer& vertices, const gl::Buffer& state);
    void validate_through(std::uint64_t frame);
    void discard_from(std::uint64_t frame);
    // Waits for every queued copy and file of validated frames, drops the rest. Throws ranryu::Error
    // if a file failed to write.
    void finish();

    std::uint64_t frames_captured() const { return queue_.captured(); }
    // The frames written so far, in frame order.
    std::vector<MeshRecord> written() const;

private:
    struct Copies {
        gl::Buffer vertices, state;
    };
    using Slot = ReadbackQueue<Copies>::Slot;   // tag: the frame
    void retire(Slot& s);
    void write(std::size_t buffer);   // the writer thread's job: one PLY

    profile::GpuTimer& timer_;
    profile::PassId pass_;
    std::filesystem::path dir_;
    std::size_t max_vertices_;
    std::vector<std::vector<gpu::MeshVertex>> buffers_;   // reused; storage grows to the largest mesh
    std::vector<MeshRecord> records_;                     // what each buffer holds
    std::vector<glm::vec3> positions_, normals_;          // the writer thread's scratch
    std::vector<glm::uvec3> triangles_;
    mutable std::mutex written_mutex_;
    std::vector<MeshRecord> written_;
    ReadbackQueue<Copies> queue_;   // last: its threads stop before the frames they write go
};

}  // namespace ranryu::record
