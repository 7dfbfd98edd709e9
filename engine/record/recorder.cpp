#include "record/recorder.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>
#include <thread>

#include "core/error.h"
#include "record/png.h"

namespace ranryu::record {
namespace fs = std::filesystem;

namespace {

bool is_run_file(const fs::path& p) {
    const std::string name = p.filename().string();
    if (name == "run.json") return true;
    return name.starts_with("frame_") && (name.ends_with(".png") || name.ends_with(".ply"));
}

}  // namespace

std::string frame_name(std::uint64_t index, const char* extension) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "frame_%05llu.%s", static_cast<unsigned long long>(index), extension);
    return buf;
}

std::size_t prepare_output(const fs::path& dir, bool force) {
    std::error_code ec;
    const std::string what = "--out " + dir.string();
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError(what + ": exists and is not a folder");
    if (!fs::exists(dir, ec)) {
        fs::create_directories(dir, ec);
        if (ec) throw InputError(what + ": cannot create the folder (" + ec.message() + ")");
    }
    // Writable? Try the way frames are written: a file created, then removed.
    const fs::path probe = dir / ".ranryu-write-test";
    {
        std::ofstream out(probe, std::ios::binary);
        if (!out || !(out << "ok") || !(out.flush()))
            throw InputError(what + ": the folder is not writable");
    }
    fs::remove(probe, ec);

    std::vector<fs::path> earlier;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file() && is_run_file(e.path())) earlier.push_back(e.path());
    if (earlier.empty()) return 0;
    if (!force)
        throw InputError(what + ": already holds an earlier run (" + std::to_string(earlier.size()) +
                         " files: frame_*.png/.ply, run.json); pass --force to replace it, or choose another folder");
    for (const fs::path& p : earlier) {
        fs::remove(p, ec);
        if (ec) throw InputError(what + ": cannot remove " + p.filename().string() + " (" + ec.message() + ")");
    }
    return earlier.size();
}

std::size_t Recorder::bytes_for(int width, int height, int ring) {
    return std::size_t(std::max(ring, 1)) * std::size_t(width) * std::size_t(height) * 4;   // RGBA8
}

Recorder::Recorder(profile::GpuTimer& timer, fs::path dir, int width, int height, bool gated,
                   std::function<void()> pump, int ring, int writers)
    : timer_(timer), pass_(timer.pass("readback")), dir_(std::move(dir)), width_(width), height_(height),
      ring_(std::size_t(std::max(ring, 1))) {
    const std::size_t bytes = bytes_for(width, height, 1);
    for (std::size_t i = 0; i < ring_.size(); ++i)
        ring_.slots()[i].data = gl::Buffer(bytes, GL_STREAM_READ, nullptr, "readback." + std::to_string(i));
    if (writers <= 0) writers = std::max(1, int(std::thread::hardware_concurrency()) - 1);
    // Enough CPU frames that every writer can be busy while the ring retires more, plus the frames a
    // gated recorder holds until their records arrive (those arrive a few frames late).
    buffers_.resize(std::size_t(writers) + ring_.size() + (gated ? 8 : 0));
    for (auto& b : buffers_) b.resize(bytes);
    writer_ = std::make_unique<GatedWriter>(
        buffers_.size(), writers, gated,
        [this](std::uint64_t frame, std::size_t b) { write_png(dir_ / frame_name(frame), width_, height_, buffers_[b].data()); },
        std::move(pump));
}

Recorder::~Recorder() {
    try {
        finish();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ranryu: %s\n", e.what());
    }
}

void Recorder::capture(const gl::RenderTarget& target) {
    if (finished_) throw Error("Recorder::capture after finish");
    if (target.width() != width_ || target.height() != height_) throw Error("Recorder: target size changed");
    auto retire_slot = [this](Slot& o) { retire(o); };
    Slot& s = ring_.acquire(retire_slot);
    {
        auto pass = timer_.scope(pass_);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, s.data.id());
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    }
    ring_.submit(captured_++, retire_slot);   // and hands over whatever the GPU has finished
}

void Recorder::retire(Slot& s) {
    const std::size_t buffer = writer_->acquire();
    glBindBuffer(GL_PIXEL_PACK_BUFFER, s.data.id());
    const auto* src = static_cast<const std::uint8_t*>(
        glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(s.data.size()), GL_MAP_READ_BIT));
    if (src) {
        // GL rows run bottom-up; PNG rows top-down.
        const std::size_t row = std::size_t(width_) * 4;
        std::uint8_t* dst = buffers_[buffer].data();
        for (int y = 0; y < height_; ++y) std::memcpy(dst + std::size_t(y) * row, src + std::size_t(height_ - 1 - y) * row, row);
        glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (!src) {
        writer_->fail("cannot map the readback buffer of frame " + std::to_string(s.tag));
        writer_->release(buffer);
        return;
    }
    writer_->submit(s.tag, buffer);
}

void Recorder::validate_through(std::uint64_t frame) { writer_->validate_through(frame); }
void Recorder::discard_from(std::uint64_t frame) { writer_->discard_from(frame); }

void Recorder::finish() {
    if (finished_) return;
    finished_ = true;
    ring_.drain([this](Slot& s) { retire(s); });
    writer_->finish();
}

std::uint64_t Recorder::frames_written() const { return writer_->written(); }

}  // namespace ranryu::record
