#pragma once
// The progress line of a run (record, profile, validate): frame i/N, simulated time, frames a wall
// second, substeps a frame and the time left. It uses only what the CPU already knows (the frame
// count, the wall clock and the latest record that pipeline.poll() collected, frames late) and never
// waits on the GPU.
//
// On a terminal the line is rewritten in place ('\r', padded over the last one) about five times a
// second and erased at the end, so that what the command prints next starts on a clean line.
// Elsewhere (a log file, a pipe) it is one plain line at most every `line_interval_s` seconds (10 by
// default): none for a shorter run. It goes to stderr, so that stdout stays the command's result.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <optional>
#include <string>

#include "frame/loop.h"

namespace ranryu::frame {

// What a line says; what is not known yet reads "-".
struct ProgressFacts {
    std::uint64_t frame = 0;                   // frames run
    std::uint64_t total = 0;                   // of this many (0: not known; then no ETA)
    std::optional<double> simulated_seconds;   // as of the latest record
    std::optional<double> fps;                 // frames a wall second, over the last few seconds
    std::optional<std::uint32_t> substeps;     // of the latest record
};
// "ranryu record: frame 37/120, t 0.617 s, 12.3 fps, 4 substeps/frame, ETA 0:07"
std::string progress_line(const std::string& label, const ProgressFacts& facts);

class Progress {
public:
    enum class Mode { quiet, terminal, lines };
    // quiet if asked, terminal if `out` is one, else lines.
    static Mode mode_for(std::FILE* out, bool quiet);

    Progress(std::string label, Mode mode, std::FILE* out = stderr, double line_interval_s = 10.0);
    ~Progress() { finish(); }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // The run's length in frames, once it is known.
    void expect(std::uint64_t total_frames) { total_ = total_frames; }
    // After each frame (FrameHooks::after): reads the clock, and writes the line when it is due.
    void update(const Pipeline& p);
    // FrameHooks whose `after` is update().
    FrameHooks hooks();
    // Erases the line on a terminal. Idempotent; the destructor calls it.
    void finish();

private:
    using Clock = std::chrono::steady_clock;
    void show(std::string line);

    std::string label_;
    Mode mode_;
    std::FILE* out_;
    Clock::duration interval_;
    std::uint64_t total_ = 0;
    Clock::time_point last_shown_;
    bool shown_ = false;
    std::size_t shown_length_ = 0;                                   // of the line on the terminal
    std::deque<std::pair<Clock::time_point, std::uint64_t>> samples_;   // (when, frames run), for fps
};

}  // namespace ranryu::frame
