#include "record/recorder.h"

#include <algorithm>
#include <exception>
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

// A run's file: its frames' files, run.json, and the reports of runs resumed into its folder.
bool is_run_file(const fs::path& p) {
    const std::string name = p.filename().string();
    if (name == "run.json") return true;
    if (name.starts_with("frame_")) return name.ends_with(".png") || name.ends_with(".ply");
    if (name.starts_with("run_from_")) return name.ends_with(".json");
    return name.starts_with("particles_") && (name.ends_with(".ply") || name.ends_with(".vtp"));
}

// A file that a run resumed at frame `first` would write or make stale: a frame's file or a resumed
// run's report numbered `first` or later.
bool written_from(const fs::path& p, std::uint64_t first) {
    const std::string name = p.filename().string();
    if (!is_run_file(p) || name == "run.json") return false;
    const std::size_t b = name.find('.'), a = name.rfind('_', b);
    if (a == std::string::npos || b == std::string::npos || b <= a + 1) return false;
    std::uint64_t index = 0;
    for (std::size_t i = a + 1; i < b; ++i) {
        if (name[i] < '0' || name[i] > '9') return false;
        index = index * 10 + std::uint64_t(name[i] - '0');
    }
    return index >= first;
}

}  // namespace

std::string frame_name(std::uint64_t index, const char* extension, const char* prefix) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s_%05llu.%s", prefix, static_cast<unsigned long long>(index), extension);
    return buf;
}

std::size_t prepare_output(const fs::path& dir, bool force) { return prepare_output(dir, force, std::nullopt); }

std::string resumed_report_name(std::uint64_t first) { return frame_name(first, "json", "run_from"); }

std::size_t prepare_output(const fs::path& dir, bool force, std::optional<std::uint64_t> resumed_at) {
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
        if (e.is_regular_file() && (resumed_at ? written_from(e.path(), *resumed_at) : is_run_file(e.path())))
            earlier.push_back(e.path());
    if (earlier.empty()) return 0;
    if (resumed_at && !force)
        throw InputError(what + ": already holds frames or reports from frame " + std::to_string(*resumed_at) + " on (" +
                         std::to_string(earlier.size()) + " files), which the resumed run would write; pass --force to replace them, or choose another folder");
    if (!force)
        throw InputError(what + ": already holds an earlier run (" + std::to_string(earlier.size()) +
                         " files: frame_*.png/.ply, particles_*.ply/.vtp, run.json, run_from_*.json); pass --force to replace it, or choose another folder");
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
                   std::function<void()> pump, int ring, int writers, FrameSinks sinks)
    : timer_(timer), pass_(timer.pass("readback")), dir_(std::move(dir)), width_(width), height_(height),
      sinks_(std::move(sinks)),
      queue_("Recorder", ring, writers > 0 ? writers : std::max(1, int(std::thread::hardware_concurrency()) - 1), gated,
             [this](std::uint64_t frame, std::size_t b) { write(frame, b); }, std::move(pump), [this](Slot& s) { retire(s); }) {
    const std::size_t bytes = bytes_for(width, height, 1);
    for (std::size_t i = 0; i < queue_.slots().size(); ++i)
        queue_.slots()[i].data = gl::Buffer(bytes, GL_STREAM_READ, nullptr, "readback." + std::to_string(i));
    buffers_.resize(queue_.buffers());
    for (auto& b : buffers_) b.resize(bytes);
}

Recorder::~Recorder() { finish_or_report([this] { finish(); }); }

// On a writer thread.
void Recorder::write(std::uint64_t frame, std::size_t b) {
    // Every frame a writer takes reaches the video, PNG failed or not: the next one waits for it.
    std::exception_ptr png_failed;
    if (sinks_.png) try {
            write_png(dir_ / frame_name(frame), width_, height_, buffers_[b].data());
        } catch (...) {
            png_failed = std::current_exception();
        }
    if (sinks_.video) sinks_.video->write(frame, buffers_[b].data());
    if (png_failed) std::rethrow_exception(png_failed);
}

void Recorder::capture(const gl::RenderTarget& target) {
    if (target.width() != width_ || target.height() != height_) throw Error("Recorder: target size changed");
    Slot& s = queue_.acquire();
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
    queue_.submit();   // and hands over whatever the GPU has finished
}

void Recorder::retire(Slot& s) {
    const std::size_t buffer = queue_.writer().acquire();
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
        if (sinks_.video) sinks_.video->abandon(s.tag);
        queue_.writer().fail("cannot map the readback buffer of frame " + std::to_string(s.tag));
        queue_.writer().release(buffer);
        return;
    }
    queue_.writer().submit(s.tag, buffer);
}

void Recorder::validate_through(std::uint64_t frame) { queue_.validate_through(frame); }
void Recorder::discard_from(std::uint64_t frame) { queue_.discard_from(frame); }

void Recorder::finish() {
    if (finished_) return;
    finished_ = true;
    // The PNGs' failure first, if any; the video is closed (and ffmpeg waited for) either way.
    std::exception_ptr failed;
    try {
        queue_.finish();
    } catch (...) {
        failed = std::current_exception();
    }
    if (sinks_.video) {
        try {
            sinks_.video->finish();
        } catch (...) {
            if (!failed) failed = std::current_exception();
        }
    }
    if (failed) std::rethrow_exception(failed);
}

std::uint64_t Recorder::frames_written() const { return queue_.writer().written(); }

}  // namespace ranryu::record
