#include "record/recorder.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

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

Recorder::Recorder(profile::GpuTimer& timer, fs::path dir, int width, int height, bool gated,
                   std::function<void()> pump, int ring, int writers)
    : timer_(timer), pass_(timer.pass("readback")), dir_(std::move(dir)), width_(width), height_(height),
      validated_end_(gated ? 0 : ~0ull), gated_(gated), pump_(std::move(pump)) {
    const std::size_t bytes = std::size_t(width) * std::size_t(height) * 4;
    ring_.resize(std::size_t(std::max(ring, 1)));
    for (std::size_t i = 0; i < ring_.size(); ++i)
        ring_[i].pbo = gl::Buffer(bytes, GL_STREAM_READ, nullptr, "readback." + std::to_string(i));
    if (writers <= 0) writers = std::max(1, int(std::thread::hardware_concurrency()) - 1);
    // Enough CPU frames that every writer can be busy while the ring retires more, plus the frames a
    // gated recorder holds until their records arrive (those arrive a few frames late).
    buffers_.resize(std::size_t(writers) + ring_.size() + (gated ? 8 : 0));
    for (std::size_t i = 0; i < buffers_.size(); ++i) {
        buffers_[i].resize(bytes);
        free_.push_back(i);
    }
    for (int i = 0; i < writers; ++i) threads_.emplace_back([this] { writer_loop(); });
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
    Slot& s = ring_[next_];
    if (s.busy) {
        s.fence.wait();   // the GPU is a whole ring behind: back-pressure
        retire(s);
    }
    {
        auto pass = timer_.scope(pass_);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, s.pbo.id());
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    }
    s.fence.insert();
    s.frame = captured_++;
    s.busy = true;
    next_ = (next_ + 1) % ring_.size();
    // Hand over, oldest first, whatever the GPU has finished; stop at the first still in flight.
    for (std::size_t k = 0; k < ring_.size(); ++k) {
        Slot& o = ring_[(next_ + k) % ring_.size()];
        if (!o.busy) continue;
        if (!o.fence.signaled()) break;
        retire(o);
    }
}

void Recorder::retire(Slot& s) {
    std::size_t buffer;
    {
        std::unique_lock lock(mutex_);
        while (free_.empty()) {   // encoders, or the records that validate frames, are behind
            if (pump_) {
                lock.unlock();
                pump_();
                lock.lock();
            }
            done_.wait_for(lock, std::chrono::milliseconds(1));
        }
        buffer = free_.back();
        free_.pop_back();
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, s.pbo.id());
    const auto* src = static_cast<const std::uint8_t*>(
        glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(s.pbo.size()), GL_MAP_READ_BIT));
    const std::size_t row = std::size_t(width_) * 4;
    std::uint8_t* dst = buffers_[buffer].data();
    if (src) {
        // GL rows run bottom-up; PNG rows top-down.
        for (int y = 0; y < height_; ++y) std::memcpy(dst + std::size_t(y) * row, src + std::size_t(height_ - 1 - y) * row, row);
        glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    s.fence.reset();
    s.busy = false;
    {
        std::lock_guard lock(mutex_);
        if (!src) {
            if (error_.empty()) error_ = "cannot map the readback buffer of frame " + std::to_string(s.frame);
            free_.push_back(buffer);
            return;
        }
        jobs_.push_back(Job{s.frame, buffer});
    }
    work_.notify_one();
}

void Recorder::writer_loop() {
    for (;;) {
        Job job;
        {
            std::unique_lock lock(mutex_);
            // Jobs are in frame order: the front one waits for validation, or is dropped.
            for (;;) {
                while (!jobs_.empty() && jobs_.front().frame >= discard_from_) {
                    free_.push_back(jobs_.front().buffer);
                    jobs_.pop_front();
                    done_.notify_all();
                }
                if (!jobs_.empty() && jobs_.front().frame < validated_end_) break;
                if (stopping_ && (jobs_.empty() || !gated_)) return;
                if (stopping_) {   // finish() after the last validation: the rest never will be
                    for (const Job& j : jobs_) free_.push_back(j.buffer);
                    jobs_.clear();
                    done_.notify_all();
                    return;
                }
                work_.wait(lock);
            }
            job = jobs_.front();
            jobs_.pop_front();
        }
        std::string failure;
        try {
            write_png(dir_ / frame_name(job.frame), width_, height_, buffers_[job.buffer].data());
        } catch (const std::exception& e) {
            failure = e.what();
        }
        {
            std::lock_guard lock(mutex_);
            free_.push_back(job.buffer);
            if (failure.empty()) ++written_;
            else if (error_.empty()) error_ = failure;
        }
        done_.notify_all();
    }
}

void Recorder::validate_through(std::uint64_t frame) {
    {
        std::lock_guard lock(mutex_);
        validated_end_ = std::max(validated_end_, frame + 1);
    }
    work_.notify_all();
}

void Recorder::discard_from(std::uint64_t frame) {
    {
        std::lock_guard lock(mutex_);
        discard_from_ = std::min(discard_from_, frame);
    }
    work_.notify_all();
}

void Recorder::finish() {
    if (finished_) return;
    finished_ = true;
    for (std::size_t k = 0; k < ring_.size(); ++k) {
        Slot& s = ring_[(next_ + k) % ring_.size()];
        if (!s.busy) continue;
        s.fence.wait();
        retire(s);
    }
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    work_.notify_all();
    for (std::thread& t : threads_) t.join();
    threads_.clear();
    if (!error_.empty()) throw Error(error_);
}

std::uint64_t Recorder::frames_written() const {
    std::lock_guard lock(mutex_);
    return written_;
}

}  // namespace ranryu::record
