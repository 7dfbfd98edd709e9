#pragma once
// Recording frames to PNG (and, through ffmpeg, to a video: record/video.h) without stalling the GPU
// pipeline.
//
// capture() queues an asynchronous glReadPixels into the next pixel-buffer object of a ring and
// fences it; a later capture() finds the fence signalled, copies the pixels out (flipping rows) into
// a preallocated CPU buffer and hands it to writer threads, which encode the PNG off the render
// thread and hand the frame to the video's ffmpeg in frame order. The render thread waits only when the whole ring is still in flight (GPU behind) or every
// CPU buffer is queued for encoding (encoders behind): back-pressure, never a per-frame stall.
//
// A frame is written only once the caller says it is sound (validate_through), so that nothing drawn
// after an instability reaches disk; discard_from() drops such frames. A recorder whose frames need
// no check is made with `gated` false.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "record/readback_queue.h"
#include "record/video.h"

namespace ranryu::record {

// Where a Recorder's frames go: PNG files in its folder (frame_00000.png, ...) and/or a video.
struct FrameSinks {
    bool png = true;
    std::unique_ptr<VideoEncoder> video;   // finished by Recorder::finish()
};

// Makes `dir` ready for a new run: creates it if missing and checks that it can be written. If it
// holds an earlier run (frame_*.png, frame_*.ply, particles_*.ply, particles_*.vtp or run.json) it
// refuses with ranryu::InputError, unless `force`, which removes that earlier run first. Returns the
// number of files removed.
std::size_t prepare_output(const std::filesystem::path& dir, bool force);
// The same for a run resumed at frame `resumed_at` (frame/checkpoint.h; nothing: a new run) into the
// folder of the run it goes on from: that run's files are kept (its frames before `resumed_at`, its
// run.json, the reports of earlier resumptions); what the resumed run would write over or leave stale
// (frames and run_from_*.json reports numbered `resumed_at` or later) is refused, unless `force`,
// which removes those.
std::size_t prepare_output(const std::filesystem::path& dir, bool force, std::optional<std::uint64_t> resumed_at);
// The resumed run's report: "run_from_00300.json" (the first run's is run.json).
std::string resumed_report_name(std::uint64_t first);

// "frame_00042.png", "particles_00042.vtp"
std::string frame_name(std::uint64_t index, const char* extension = "png", const char* prefix = "frame");

class Recorder {
public:
    // `writers` = 0 picks one per spare hardware thread.
    // `pump` is called while the render thread waits for a free CPU buffer, so that the caller can
    // collect the records that validate frames (which frees buffers) instead of deadlocking.
    Recorder(profile::GpuTimer& timer, std::filesystem::path dir, int width, int height, bool gated,
             std::function<void()> pump = {}, int ring = 3, int writers = 0, FrameSinks sinks = {});
    ~Recorder();
    // Device memory the constructor allocates: its readback ring (frame/memory.h).
    static std::size_t bytes_for(int width, int height, int ring = 3);
    Recorder(const Recorder&) = delete;
    Recorder& operator=(const Recorder&) = delete;

    // Pass "readback": reads `target`'s colour into the ring as frame number frames_captured().
    // Numbers the first capture `frame` (the files' names and the frames validate_through() and
    // discard_from() name): a run resumed from a checkpoint (frame/checkpoint.h). Before any capture.
    void start_at(std::uint64_t frame) {
        queue_.start_at(frame);
        if (sinks_.video) sinks_.video->start_at(frame);
    }
    void capture(const gl::RenderTarget& target);
    // Frames up to and including `frame` may be written.
    void validate_through(std::uint64_t frame);
    // Frames from `frame` on are never written (they show an unstable simulation).
    void discard_from(std::uint64_t frame);
    // Waits for every queued readback and PNG of validated frames and drops the rest, then finishes
    // the video. Throws ranryu::Error if any file failed to write or ffmpeg failed.
    void finish();

    std::uint64_t frames_captured() const { return queue_.captured(); }
    std::uint64_t frames_written() const;   // frames written to every sink
    const VideoEncoder* video() const { return sinks_.video.get(); }

private:
    using Slot = ReadbackQueue<gl::Buffer>::Slot;   // data: the pixel-buffer object; tag: the frame
    void retire(Slot& s);   // fence signalled (or waited): copy out and queue for encoding
    void write(std::uint64_t frame, std::size_t buffer);   // a writer thread's job: the PNG, then the video

    profile::GpuTimer& timer_;
    profile::PassId pass_;
    std::filesystem::path dir_;
    int width_, height_;
    std::vector<std::vector<std::uint8_t>> buffers_;   // preallocated frames, named by the writer's indices
    FrameSinks sinks_;
    ReadbackQueue<gl::Buffer> queue_;   // last: its threads stop before the frames and sinks they use go
    bool finished_ = false;
};

}  // namespace ranryu::record
