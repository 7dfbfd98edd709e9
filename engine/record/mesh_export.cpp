#include "record/mesh_export.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "record/recorder.h"
#include "surface/ply.h"

namespace ranryu::record {

namespace {
// GL 4.3 (no direct state access): maps go through the copy binding points.
// Copies the first `bytes` of `from` into dst; false if the buffer could not be mapped.
bool read_mapped(const gl::Buffer& from, void* dst, std::size_t bytes) {
    glBindBuffer(GL_COPY_READ_BUFFER, from.id());
    const void* p = glMapBufferRange(GL_COPY_READ_BUFFER, 0, GLsizeiptr(bytes), GL_MAP_READ_BIT);
    bool ok = p != nullptr;
    if (p) {
        std::memcpy(dst, p, bytes);
        ok = glUnmapBuffer(GL_COPY_READ_BUFFER) == GL_TRUE;
    }
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    return ok;
}
}  // namespace

std::size_t MeshExporter::bytes_for(std::size_t max_vertices, int ring) {
    return std::size_t(std::max(ring, 1)) * (max_vertices * sizeof(gpu::MeshVertex) + sizeof(gpu::MeshState));
}

MeshExporter::MeshExporter(profile::GpuTimer& timer, std::filesystem::path dir, std::size_t max_vertices, bool gated,
                           std::function<void()> pump, int ring)
    : timer_(timer), pass_(timer.pass("mesh-readback")), dir_(std::move(dir)), max_vertices_(max_vertices),
      queue_("MeshExporter", ring, 1, gated, [this](std::uint64_t, std::size_t b) { write(b); }, std::move(pump),
             [this](Slot& s) { retire(s); }) {
    for (std::size_t i = 0; i < queue_.slots().size(); ++i) {
        Copies& c = queue_.slots()[i].data;
        c.vertices = gl::Buffer(max_vertices_ * sizeof(gpu::MeshVertex), GL_STREAM_READ, nullptr,
                                "mesh-readback.vertices." + std::to_string(i));
        c.state = gl::Buffer(sizeof(gpu::MeshState), GL_STREAM_READ, nullptr, "mesh-readback.state." + std::to_string(i));
    }
    buffers_.resize(queue_.buffers());   // their storage grows to the largest mesh, then stays
    records_.resize(buffers_.size());
}

MeshExporter::~MeshExporter() { finish_or_report([this] { finish(); }); }

void MeshExporter::capture(const gl::Buffer& vertices, const gl::Buffer& state) {
    if (vertices.size() < max_vertices_ * sizeof(gpu::MeshVertex)) throw Error("MeshExporter: vertex buffer smaller than its capacity");
    Slot& s = queue_.acquire();
    {
        auto pass = timer_.scope(pass_);
        // The mesh passes end with their own barriers; copies read buffer data after them in order.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        gl::copy_buffer(state, s.data.state, sizeof(gpu::MeshState));
        gl::copy_buffer(vertices, s.data.vertices, s.data.vertices.size());
    }
    queue_.submit();
}

void MeshExporter::retire(Slot& s) {
    const std::size_t buffer = queue_.writer().acquire();
    gpu::MeshState state{};
    bool ok = read_mapped(s.data.state, &state, sizeof state);
    records_[buffer] = MeshRecord{s.tag, std::min<std::uint32_t>(state.draw.x, std::uint32_t(max_vertices_)),
                                  state.totals.z != 0, state.totals.w != 0};
    std::vector<gpu::MeshVertex>& dst = buffers_[buffer];
    dst.resize(records_[buffer].vertices);   // reuses the storage once it has grown to the largest mesh
    if (ok && !dst.empty()) ok = read_mapped(s.data.vertices, dst.data(), dst.size() * sizeof(gpu::MeshVertex));
    if (!ok) {
        queue_.writer().fail("cannot map the mesh readback buffers of frame " + std::to_string(s.tag));
        queue_.writer().release(buffer);
        return;
    }
    queue_.writer().submit(s.tag, buffer);
}

// On the writer thread (the only one, so the scratch arrays need no lock).
void MeshExporter::write(std::size_t buffer) {
    const std::vector<gpu::MeshVertex>& soup = buffers_[buffer];
    const std::size_t n = soup.size() - soup.size() % 3;
    positions_.resize(n);
    normals_.resize(n);
    triangles_.resize(n / 3);
    for (std::size_t i = 0; i < n; ++i) {
        positions_[i] = glm::vec3(soup[i].position);
        normals_[i] = glm::vec3(soup[i].normal);
    }
    for (std::size_t t = 0; t < n / 3; ++t) triangles_[t] = glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2);
    surface::write_ply(dir_ / frame_name(records_[buffer].frame, "ply"), positions_, normals_, triangles_);
    std::lock_guard lock(written_mutex_);
    written_.push_back(records_[buffer]);
}

void MeshExporter::validate_through(std::uint64_t frame) { queue_.validate_through(frame); }
void MeshExporter::discard_from(std::uint64_t frame) { queue_.discard_from(frame); }
void MeshExporter::finish() { queue_.finish(); }

std::vector<MeshRecord> MeshExporter::written() const {
    std::lock_guard lock(written_mutex_);
    return written_;
}

}  // namespace ranryu::record
