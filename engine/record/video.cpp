#include "record/video.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "core/error.h"

extern char** environ;

namespace ranryu::record {
namespace fs = std::filesystem;

fs::path find_on_path(const std::string& name) {
    const char* path = std::getenv("PATH");
    if (!path) return {};
    std::istringstream dirs(path);
    for (std::string dir; std::getline(dirs, dir, ':');) {
        if (dir.empty()) continue;
        const fs::path p = fs::path(dir) / name;
        std::error_code ec;
        if (fs::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0) return p;
    }
    return {};
}

std::string frame_rate(double frame_dt) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", 1.0 / frame_dt);
    return buf;
}

VideoPlan VideoPlan::check(const fs::path& file, bool force) {
    const std::string what = "--video " + file.string();
    VideoPlan plan;
    plan.file = file;
    const std::string ext = file.extension().string();
    if (ext == ".mp4") plan.format = VideoFormat::mp4;
    else if (ext == ".webm") plan.format = VideoFormat::webm;
    else if (ext == ".gif") plan.format = VideoFormat::gif;
    else throw InputError(what + ": unknown video type \"" + ext + "\"; the file must end in .mp4 (H.264), .webm (VP9) or .gif");
    plan.ffmpeg = find_on_path("ffmpeg");
    if (plan.ffmpeg.empty())
        throw InputError(what + ": ffmpeg is not installed (no ffmpeg on PATH); install it (Debian: apt-get install "
                                "ffmpeg, or scripts/install-deps.sh) or record without --video");
    std::error_code ec;
    if (fs::is_directory(file, ec)) throw InputError(what + ": is a folder");
    if (fs::exists(file, ec) && !force)
        throw InputError(what + ": the file exists; pass --force to replace it, or choose another name");
    return plan;
}

void VideoPlan::prepare() const {
    const std::string what = "--video " + file.string();
    std::error_code ec;
    const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
    if (!fs::exists(dir, ec)) {
        fs::create_directories(dir, ec);
        if (ec) throw InputError(what + ": cannot create its folder (" + ec.message() + ")");
    }
    if (fs::exists(file, ec)) {   // check() let it through: --force
        fs::remove(file, ec);
        if (ec) throw InputError(what + ": cannot remove the earlier file (" + ec.message() + ")");
    }
    // Writable? Create the file as ffmpeg will, then leave the name free for it.
    const int fd = open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError(what + ": cannot write the file (" + std::strerror(errno) + ")");
    close(fd);
    fs::remove(file, ec);
}

const char* VideoPlan::codec() const {
    switch (format) {
        case VideoFormat::mp4: return "libx264";
        case VideoFormat::webm: return "libvpx-vp9";
        case VideoFormat::gif: return "gif";
    }
    return "";
}

VideoEncoder::VideoEncoder(const VideoPlan& plan, int width, int height, double frame_dt)
    : plan_(plan), bytes_(std::size_t(width) * std::size_t(height) * 4) {
    // A dead ffmpeg must fail a write (EPIPE), not end ranryu.
    std::signal(SIGPIPE, SIG_IGN);

    const std::string even = "pad=ceil(iw/2)*2:ceil(ih/2)*2";   // yuv420p wants even sizes
    argv_ = {plan.ffmpeg.string(), "-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgba",
             "-s", std::to_string(width) + "x" + std::to_string(height), "-r", frame_rate(frame_dt), "-i", "pipe:0"};
    switch (plan.format) {
        case VideoFormat::mp4:
            argv_.insert(argv_.end(), {"-vf", even, "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18",
                                       "-movflags", "+faststart"});
            break;
        case VideoFormat::webm:
            argv_.insert(argv_.end(), {"-vf", even, "-c:v", "libvpx-vp9", "-pix_fmt", "yuv420p", "-crf", "32", "-b:v", "0",
                                       "-deadline", "good", "-cpu-used", "4", "-row-mt", "1"});
            break;
        case VideoFormat::gif:
            argv_.insert(argv_.end(), {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse", "-loop", "0"});
            break;
    }
    // -n: never overwrite (prepare() freed the name); an absolute path, never read as an option.
    argv_.insert(argv_.end(), {"-n", fs::absolute(plan.file).string()});

    const std::string what = "--video " + plan.file.string() + ": cannot start ffmpeg (" + plan.ffmpeg.string() + "): ";
    int pipe_fds[2];
    if (pipe2(pipe_fds, O_CLOEXEC) != 0) throw Error(what + std::strerror(errno));
#ifdef F_SETPIPE_SZ
    fcntl(pipe_fds[1], F_SETPIPE_SZ, 1 << 20);   // fewer wake-ups per frame; a hint, may be refused
#endif
    err_ = std::tmpfile();   // unlinked: nothing is left behind
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attr;
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attr);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    if (err_) posix_spawn_file_actions_adddup2(&actions, fileno(err_), 2);
    else posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    // Its own process group (the terminal's Ctrl-C is ranryu's to handle), default signal actions and
    // no blocked signals.
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    for (int s : {SIGPIPE, SIGINT, SIGTERM}) sigaddset(&defaults, s);
    posix_spawnattr_setpgroup(&attr, 0);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    std::vector<char*> args;
    for (std::string& a : argv_) args.push_back(a.data());
    args.push_back(nullptr);
    const int rc = posix_spawn(&pid_, argv_[0].c_str(), &actions, &attr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    close(pipe_fds[0]);
    if (rc != 0) {
        close(pipe_fds[1]);
        if (err_) std::fclose(err_);
        err_ = nullptr;
        pid_ = -1;
        throw Error(what + std::strerror(rc));
    }
    fd_ = pipe_fds[1];
}

VideoEncoder::~VideoEncoder() {
    close_and_wait();
    if (err_) std::fclose(err_);
}

void VideoEncoder::start_at(std::uint64_t frame) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (written_ != 0) throw Error("VideoEncoder::start_at after a frame was written");
    next_ = frame;
}

void VideoEncoder::write(std::uint64_t frame, const std::uint8_t* rgba) {
    std::unique_lock lock(mutex_);
    turn_.wait(lock, [&] { return next_ == frame || !broken_.empty(); });
    if (broken_.empty()) {
        // The writers wait for their turn anyway: writing under the lock costs nothing.
        for (std::size_t done = 0; done < bytes_;) {
            const ssize_t n = ::write(fd_, rgba + done, bytes_ - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                broken_ = "ffmpeg stopped reading frames at frame " + std::to_string(frame) + " (" +
                          std::strerror(errno) + ")";
                break;
            }
            done += std::size_t(n);
        }
        if (broken_.empty()) ++written_;
    }
    next_ = frame + 1;
    turn_.notify_all();
}

void VideoEncoder::abandon(std::uint64_t frame) {
    {
        std::lock_guard lock(mutex_);
        if (broken_.empty()) broken_ = "frame " + std::to_string(frame) + " could not be read back, so the video lacks it";
    }
    turn_.notify_all();
}

void VideoEncoder::close_and_wait() {
    if (fd_ >= 0) close(fd_);   // end of input: ffmpeg finishes the file
    fd_ = -1;
    if (pid_ > 0)
        while (waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
        }
    pid_ = -1;
}

std::string VideoEncoder::stderr_tail() {
    if (!err_) return {};
    std::fflush(err_);
    std::rewind(err_);
    std::string text, line, last;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, err_)) > 0;) text.append(buf, n);
    std::istringstream lines(text);
    while (std::getline(lines, line))
        if (!line.empty()) last = line;
    return last;
}

void VideoEncoder::finish() {
    if (finished_) return;
    finished_ = true;
    close_and_wait();
    const std::string what = "--video " + plan_.file.string() + ": ";
    std::string failure;
    if (WIFEXITED(status_) && WEXITSTATUS(status_) != 0)
        failure = "ffmpeg failed with exit status " + std::to_string(WEXITSTATUS(status_));
    else if (WIFSIGNALED(status_))
        failure = "ffmpeg was killed by signal " + std::to_string(WTERMSIG(status_));
    std::lock_guard lock(mutex_);
    if (failure.empty() && broken_.empty()) return;
    if (failure.empty()) failure = broken_;
    else if (!broken_.empty()) failure += "; " + broken_;
    failure += " after taking " + std::to_string(written_) + " frames";
    const std::string said = stderr_tail();
    throw Error(what + failure + (said.empty() ? std::string() : ": " + said));
}

std::uint64_t VideoEncoder::frames_written() const {
    std::lock_guard lock(mutex_);
    return written_;
}

}  // namespace ranryu::record
