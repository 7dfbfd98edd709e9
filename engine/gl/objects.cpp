#include "gl/objects.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <string>

#include "core/error.h"
#include "gl/faults.h"

namespace ranryu::gl {

namespace {
std::atomic<std::uint64_t> g_allocated{0}, g_peak{0};
}  // namespace

std::uint64_t allocated_bytes() { return g_allocated.load(); }
std::uint64_t peak_allocated_bytes() { return g_peak.load(); }

TrackedBytes::TrackedBytes(std::size_t bytes) : bytes_(bytes) {
    const std::uint64_t now = g_allocated += bytes;
    std::uint64_t peak = g_peak.load();
    while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {}
}
void TrackedBytes::release() {
    g_allocated -= bytes_;
    bytes_ = 0;
}

void label(GLenum identifier, GLuint name, std::string_view text) {
    if (!text.empty() && name != 0) glObjectLabel(identifier, name, GLsizei(text.size()), text.data());
}

Buffer::Buffer(std::size_t bytes, GLenum usage, const void* data, std::string_view name)
    : size_(bytes), tracked_(bytes == 0 ? 4 : bytes) {
    GLuint id = 0;
    glGenBuffers(1, &id);
    name_ = Name<DeleteBuffer>(id);
    // Any target works for allocation; COPY_WRITE_BUFFER leaves the binding points used by passes alone.
    glBindBuffer(GL_COPY_WRITE_BUFFER, id);
    glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(bytes == 0 ? 4 : bytes), data, usage);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    label(GL_BUFFER, id, name);
}

void Buffer::upload(const void* data, std::size_t bytes, std::size_t offset) {
    if (offset + bytes > size_)
        throw Error("Buffer::upload past the end (" + std::to_string(offset + bytes) + " > " +
                    std::to_string(size_) + " bytes)");
    glBindBuffer(GL_COPY_WRITE_BUFFER, id());
    glBufferSubData(GL_COPY_WRITE_BUFFER, GLintptr(offset), GLsizeiptr(bytes), data);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

void Buffer::read_bytes(void* dst, std::size_t bytes, std::size_t offset) const {
    if (offset + bytes > size_)
        throw Error("Buffer::read past the end (" + std::to_string(offset + bytes) + " > " +
                    std::to_string(size_) + " bytes)");
    if (bytes == 0) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);   // what shaders wrote, before the copies
    // In pieces of at most kStagingBytes, so that reading a buffer near the device's memory (a
    // checkpoint's) does not need as much again.
    constexpr std::size_t kStagingBytes = std::size_t(32) << 20;
    const Buffer staging(std::min(bytes, kStagingBytes), GL_STREAM_READ, nullptr, "read.staging");
    for (std::size_t done = 0; done < bytes;) {
        const std::size_t piece = std::min(bytes - done, kStagingBytes);
        copy_buffer(*this, staging, piece, offset + done, 0);
        staging.read_own_bytes(static_cast<char*>(dst) + done, piece, 0);
        done += piece;
    }
}

void Buffer::read_own_bytes(void* dst, std::size_t bytes, std::size_t offset) const {
    if (offset + bytes > size_)
        throw Error("Buffer::read past the end (" + std::to_string(offset + bytes) + " > " +
                    std::to_string(size_) + " bytes)");
    if (bytes == 0) return;
    // No memory barrier: this storage is written by copies (whose writes GL orders before this read),
    // not by shaders, and on llvmpipe a barrier waits for all queued work.
    glBindBuffer(GL_COPY_READ_BUFFER, id());
    glGetBufferSubData(GL_COPY_READ_BUFFER, GLintptr(offset), GLsizeiptr(bytes), dst);
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
}

void copy_buffer(const Buffer& from, const Buffer& to, std::size_t bytes, std::size_t from_offset, std::size_t to_offset) {
    glBindBuffer(GL_COPY_READ_BUFFER, from.id());
    glBindBuffer(GL_COPY_WRITE_BUFFER, to.id());
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, GLintptr(from_offset), GLintptr(to_offset), GLsizeiptr(bytes));
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

Texture2D::Texture2D(GLenum internal_format, int width, int height, std::string_view name)
    : width_(width), height_(height), tracked_(std::size_t(width) * std::size_t(height) * texel_bytes(internal_format)) {
    GLuint id = 0;
    glGenTextures(1, &id);
    name_ = Name<DeleteTexture>(id);
    glBindTexture(GL_TEXTURE_2D, id);
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
    label(GL_TEXTURE, id, name);
}

std::size_t Texture2D::texel_bytes(GLenum internal_format) {
    switch (internal_format) {
        case GL_RGBA16F: case GL_RG32F: return 8;
        case GL_RGBA32F: return 16;
        case GL_R8: return 1;
        case GL_RG8: case GL_R16F: return 2;
        default: return 4;   // RGBA8, DEPTH_COMPONENT32F, R32F, R32UI, DEPTH24_STENCIL8
    }
}

std::size_t RenderTarget::bytes_for(int width, int height) {
    return std::size_t(width) * std::size_t(height) *
           (Texture2D::texel_bytes(kColorFormat) + Texture2D::texel_bytes(kDepthFormat));
}

Framebuffer::Framebuffer(std::span<const Texture2D* const> colors, const Texture2D* depth, std::string_view name) {
    GLuint id = 0;
    glGenFramebuffers(1, &id);
    name_ = Name<DeleteFramebuffer>(id);
    glBindFramebuffer(GL_FRAMEBUFFER, id);
    std::vector<GLenum> buffers;
    for (const Texture2D* c : colors) {
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(buffers.size());
        glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, c->id(), 0);
        buffers.push_back(attachment);
    }
    if (depth) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth->id(), 0);
    glDrawBuffers(GLsizei(buffers.size()), buffers.data());
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error("framebuffer " + std::string(name) + " is incomplete (status 0x" + std::to_string(status) + ")");
    label(GL_FRAMEBUFFER, id, name);
}

RenderTarget::RenderTarget(int width, int height, std::string_view name)
    : color_(kColorFormat, width, height, std::string(name) + ".color"),
      depth_(kDepthFormat, width, height, std::string(name) + ".depth") {
    const Texture2D* colors[] = {&color_};
    fbo_ = Framebuffer(colors, &depth_, std::string(name));
}

VertexArray::VertexArray() {
    GLuint id = 0;
    glGenVertexArrays(1, &id);
    name_ = Name<DeleteVertexArray>(id);
}

Queries::Queries(std::size_t count) : names_(count) {
    if (count) glGenQueries(GLsizei(count), names_.data());
}
void Queries::grow(std::size_t count) {
    const std::size_t old = names_.size();
    names_.resize(old + count);
    glGenQueries(GLsizei(count), names_.data() + old);
}

Queries& Queries::operator=(Queries&& o) noexcept {
    if (this != &o) {
        if (!names_.empty()) glDeleteQueries(GLsizei(names_.size()), names_.data());
        names_ = std::move(o.names_);
    }
    return *this;
}
Queries::~Queries() {
    if (!names_.empty()) glDeleteQueries(GLsizei(names_.size()), names_.data());
}

Fence& Fence::operator=(Fence&& o) noexcept {
    if (this != &o) {
        reset();
        sync_ = std::exchange(o.sync_, nullptr);
    }
    return *this;
}
Fence::~Fence() { reset(); }
void Fence::reset() {
    if (sync_) glDeleteSync(sync_);
    sync_ = nullptr;
}
void Fence::insert() {
    reset();
    sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}
bool Fence::signaled() const {
    if (!sync_) return true;
    const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}
void Fence::wait(const std::string& what) const {
    if (!sync_) return;
    wait_or_fault(
        [&] {
            const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 50'000'000ull);   // 50 ms slices
            if (r == GL_WAIT_FAILED) throw GpuFault("glClientWaitSync failed waiting for " + what);
            return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
        },
        std::chrono::duration<double>(fence_timeout_seconds()), what);
}

}  // namespace ranryu::gl
