#include "frame/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>

namespace ranryu::frame {
namespace {

using Seconds = std::chrono::duration<double>;
constexpr Seconds kTerminalInterval{0.2};   // redraws on a terminal
constexpr Seconds kSampleInterval{0.25};    // between the fps samples kept
constexpr Seconds kFpsWindow{10.0};         // fps over about this much of the recent past

std::string printf_string(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

// 0:07, 12:34, 1:02:03
std::string clock_time(double seconds) {
    const long s = std::lround(std::max(seconds, 0.0));
    char buf[32];
    if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    else std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
    return buf;
}

}  // namespace

std::string progress_line(const std::string& label, const ProgressFacts& f) {
    std::string line = label + ": frame " + std::to_string(f.frame);
    if (f.total) line += "/" + std::to_string(f.total);
    line += ", t " + (f.simulated_seconds ? printf_string("%.3f", *f.simulated_seconds) : "-") + " s";
    line += ", " + (f.fps ? printf_string(*f.fps < 100.0 ? "%.1f" : "%.0f", *f.fps) : "-") + " fps";
    line += ", " + (f.substeps ? std::to_string(*f.substeps) : "-") + " substeps/frame";
    if (f.total) {
        const bool known = f.fps && *f.fps > 0.0 && f.frame <= f.total;
        line += ", ETA " + (known ? clock_time(double(f.total - f.frame) / *f.fps) : "-");
    }
    return line;
}

Progress::Mode Progress::mode_for(std::FILE* out, bool quiet) {
    if (quiet) return Mode::quiet;
    return isatty(fileno(out)) ? Mode::terminal : Mode::lines;
}

Progress::Progress(std::string label, Mode mode, std::FILE* out, double line_interval_s)
    : label_(std::move(label)),
      mode_(mode),
      out_(out),
      interval_(std::chrono::duration_cast<Clock::duration>(
          mode == Mode::terminal ? kTerminalInterval : Seconds(std::max(line_interval_s, 0.0)))),
      last_shown_(Clock::now()) {}

void Progress::update(const Pipeline& p) {
    if (mode_ == Mode::quiet) return;
    const Clock::time_point now = Clock::now();
    const std::uint64_t frame = p.frames();
    if (samples_.empty() || now - samples_.back().first >= kSampleInterval) samples_.emplace_back(now, frame);
    while (samples_.size() > 2 && now - samples_[1].first >= kFpsWindow) samples_.pop_front();

    // A terminal shows the first frame and the last at once; a log waits the interval.
    const bool last = total_ && frame >= total_;
    const bool due = now - last_shown_ >= interval_ || (mode_ == Mode::terminal && (!shown_ || last));
    if (!due) return;
    ProgressFacts f;
    f.frame = frame;
    f.total = total_;
    f.substeps = p.substeps_per_frame();
    if (f.substeps) f.simulated_seconds = p.simulated_time();
    const auto& [t0, frame0] = samples_.front();
    const double span = Seconds(now - t0).count();
    if (frame > frame0 && span > 0.0) f.fps = double(frame - frame0) / span;
    last_shown_ = now;
    show(progress_line(label_, f));
}

FrameHooks Progress::hooks() {
    FrameHooks h;
    h.after = [this](Pipeline& p) { update(p); };
    return h;
}

void Progress::show(std::string line) {
    if (mode_ == Mode::lines) {
        std::fprintf(out_, "%s\n", line.c_str());
    } else {
        // Within the terminal's width: a wrapped line would not be rewritten in place.
        winsize ws{};
        if (ioctl(fileno(out_), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 1 && line.size() >= ws.ws_col) line.resize(ws.ws_col - 1u);
        const std::size_t length = line.size();
        if (length < shown_length_) line.append(shown_length_ - length, ' ');
        std::fprintf(out_, "\r%s", line.c_str());
        shown_length_ = length;
    }
    std::fflush(out_);
    shown_ = true;
}

void Progress::finish() {
    if (mode_ != Mode::terminal || !shown_) return;
    std::fprintf(out_, "\r%s\r", std::string(shown_length_, ' ').c_str());
    std::fflush(out_);
    shown_ = false;
    shown_length_ = 0;
}

}  // namespace ranryu::frame
