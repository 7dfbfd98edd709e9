#pragma once
// Move-only RAII owners of GL object names. Copying is deleted; the destructor deletes the name.
// Every wrapper requires a current context for its whole lifetime: destroy GL objects before the
// context that made them.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gl/gl.h"

namespace ranryu::gl {

// One GL name with a deleter. `Delete` is a stateless functor: void operator()(GLuint).
template <class Delete>
class Name {
public:
    Name() = default;
    explicit Name(GLuint id) : id_(id) {}
    Name(const Name&) = delete;
    Name& operator=(const Name&) = delete;
    Name(Name&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    Name& operator=(Name&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
        }
        return *this;
    }
    ~Name() { reset(); }
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_) Delete{}(id_);
        id_ = 0;
    }

private:
    GLuint id_ = 0;
};

struct DeleteBuffer { void operator()(GLuint n) const { glDeleteBuffers(1, &n); } };
struct DeleteTexture { void operator()(GLuint n) const { glDeleteTextures(1, &n); } };
struct DeleteFramebuffer { void operator()(GLuint n) const { glDeleteFramebuffers(1, &n); } };
struct DeleteVertexArray { void operator()(GLuint n) const { glDeleteVertexArrays(1, &n); } };
struct DeleteQuery { void operator()(GLuint n) const { glDeleteQueries(1, &n); } };
struct DeleteProgram { void operator()(GLuint n) const { glDeleteProgram(n); } };
struct DeleteShader { void operator()(GLuint n) const { glDeleteShader(n); } };

// Bytes of GL buffer and texture storage alive now, and the most alive at once since the process
// started: what `profile` prints as allocated, and what frame/memory.h's estimate is checked against.
std::uint64_t allocated_bytes();
std::uint64_t peak_allocated_bytes();

// Counts `bytes` into allocated_bytes() for as long as it lives; moves with its owner.
class TrackedBytes {
public:
    TrackedBytes() = default;
    explicit TrackedBytes(std::size_t bytes);
    TrackedBytes(const TrackedBytes&) = delete;
    TrackedBytes& operator=(const TrackedBytes&) = delete;
    TrackedBytes(TrackedBytes&& o) noexcept : bytes_(std::exchange(o.bytes_, 0)) {}
    TrackedBytes& operator=(TrackedBytes&& o) noexcept {
        if (this != &o) {
            release();
            bytes_ = std::exchange(o.bytes_, 0);
        }
        return *this;
    }
    ~TrackedBytes() { release(); }

private:
    void release();
    std::size_t bytes_ = 0;
};

// Attaches a debugger-visible label (KHR_debug, core 4.3) to a GL object.
void label(GLenum identifier, GLuint name, std::string_view text);

// A linear buffer. Usage hints follow the GL meaning: DYNAMIC_DRAW for per-frame uploads,
// STATIC/DYNAMIC_COPY for GPU-written data, STREAM_READ for readback.
class Buffer {
public:
    Buffer() = default;
    Buffer(std::size_t bytes, GLenum usage, const void* data = nullptr, std::string_view name = {});
    template <class T>
    static Buffer from(std::span<const T> data, GLenum usage, std::string_view name = {}) {
        return Buffer(data.size_bytes(), usage, data.data(), name);
    }

    GLuint id() const { return name_.id(); }
    std::size_t size() const { return size_; }
    explicit operator bool() const { return bool(name_); }

    // Replaces [offset, offset + bytes). Never reallocates.
    void upload(const void* data, std::size_t bytes, std::size_t offset = 0);
    // Replaces sizeof(T) bytes at `offset` with one value (a parameter struct).
    template <class T>
    void upload_value(const T& value, std::size_t offset = 0) { upload(&value, sizeof(T), offset); }

    void bind_base(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }
    void bind_range(GLenum target, GLuint index, std::size_t offset, std::size_t bytes) const {
        glBindBufferRange(target, index, id(), GLintptr(offset), GLsizeiptr(bytes));
    }

    // Synchronous read of [offset, offset + count·sizeof(T)). Waits for the GPU: tests, tools and
    // shutdown only, never the frame path. Goes through a staging buffer the GPU copies into, so that
    // this buffer is never read by the CPU itself: NVIDIA's driver (580, the H200) copies or moves a
    // buffer the CPU reads or writes from video into host memory, and a test that uploaded into such a
    // buffer between its synchronous reads saw the upload overtake a dispatch queued before it
    // (docs/PERFORMANCE.md "A buffer the CPU reads, and the GL tests on the H200").
    template <class T>
    std::vector<T> read(std::size_t count, std::size_t offset = 0) const {
        std::vector<T> out(count);
        read_bytes(out.data(), count * sizeof(T), offset);
        return out;
    }
    void read_bytes(void* dst, std::size_t bytes, std::size_t offset = 0) const;
    // The same read from this buffer's own storage, with no staging copy: for buffers made to be read
    // by the CPU (GL_STREAM_READ: the readback rings' slots), once their fence has signalled, when it
    // does not wait.
    void read_own_bytes(void* dst, std::size_t bytes, std::size_t offset = 0) const;

private:
    Name<DeleteBuffer> name_;
    std::size_t size_ = 0;
    TrackedBytes tracked_;
};

// Queues a GPU-side copy of `bytes` from `from` at `from_offset` to `to` at `to_offset`
// (glCopyBufferSubData through the copy binding points: GL 4.3 has no direct state access). Issues no
// barrier: a caller that copies what a shader wrote calls glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT) first.
void copy_buffer(const Buffer& from, const Buffer& to, std::size_t bytes, std::size_t from_offset = 0, std::size_t to_offset = 0);

// An immutable-storage 2D texture (glTexStorage2D).
class Texture2D {
public:
    Texture2D() = default;
    Texture2D(GLenum internal_format, int width, int height, std::string_view name = {});
    GLuint id() const { return name_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }
    // Bytes of one texel of `internal_format` (the formats ranryu uses; 4 otherwise).
    static std::size_t texel_bytes(GLenum internal_format);

private:
    Name<DeleteTexture> name_;
    int width_ = 0, height_ = 0;
    TrackedBytes tracked_;
};

// A framebuffer of textures: colour attachments 0, 1, ... in the order given (all drawn to), and an
// optional depth texture. Throws Error when the driver finds it incomplete.
class Framebuffer {
public:
    Framebuffer() = default;
    Framebuffer(std::span<const Texture2D* const> colors, const Texture2D* depth, std::string_view name = {});
    GLuint id() const { return name_.id(); }

private:
    Name<DeleteFramebuffer> name_;
};

// A framebuffer with one RGBA8 colour and a 32-bit float depth attachment, both textures.
class RenderTarget {
public:
    RenderTarget() = default;
    RenderTarget(int width, int height, std::string_view name = {});
    // The storage a width x height target allocates: its colour and depth textures.
    static std::size_t bytes_for(int width, int height);
    GLuint framebuffer() const { return fbo_.id(); }
    const Texture2D& color() const { return color_; }
    const Texture2D& depth() const { return depth_; }
    int width() const { return color_.width(); }
    int height() const { return color_.height(); }

private:
    static constexpr GLenum kColorFormat = GL_RGBA8, kDepthFormat = GL_DEPTH_COMPONENT32F;
    Texture2D color_, depth_;
    Framebuffer fbo_;
};

class VertexArray {
public:
    VertexArray();
    GLuint id() const { return name_.id(); }

private:
    Name<DeleteVertexArray> name_;
};

// A block of query names, made in one call.
class Queries {
public:
    Queries() = default;
    explicit Queries(std::size_t count);
    GLuint operator[](std::size_t i) const { return names_[i]; }
    std::size_t size() const { return names_.size(); }
    void grow(std::size_t count);   // appends `count` new names
    Queries(const Queries&) = delete;
    Queries& operator=(const Queries&) = delete;
    Queries(Queries&& o) noexcept : names_(std::move(o.names_)) {}
    Queries& operator=(Queries&& o) noexcept;
    ~Queries();

private:
    std::vector<GLuint> names_;
};

// A fence in the GL command stream. Polled without waiting by `signaled()`.
class Fence {
public:
    Fence() = default;
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;
    Fence(Fence&& o) noexcept : sync_(std::exchange(o.sync_, nullptr)) {}
    Fence& operator=(Fence&& o) noexcept;
    ~Fence();
    void insert();                  // replaces any earlier fence
    bool pending() const { return sync_ != nullptr; }
    bool signaled() const;          // non-blocking poll; flushes so the fence can complete
    // Blocks: back-pressure and shutdown only. After gl::fence_timeout_seconds() throws gl::GpuFault
    // naming `what` (gl/faults.h) instead of waiting forever.
    void wait(const std::string& what = "a GL fence") const;
    void reset();

private:
    GLsync sync_ = nullptr;
};

}  // namespace ranryu::gl
