#pragma once
// Video from the recorded frames: `ranryu record --video FILE` pipes every frame to Debian's ffmpeg,
// run as a child process (posix_spawn, an argv, no shell), as raw RGBA on its standard input:
//
//     ffmpeg -hide_banner -loglevel error -f rawvideo -pix_fmt rgba -s WxH -r FPS -i pipe:0 CODEC -n FILE
//
// CODEC by FILE's extension: .mp4 H.264 (libx264, yuv420p, CRF 18), .webm VP9 (libvpx-vp9, yuv420p,
// CRF 32), both padded to even sizes as yuv420p needs (an odd size gains a black row or column), and
// .gif with a palette made for the whole clip (palettegen/paletteuse: ffmpeg holds every frame
// until the end, so keep GIFs short and small; GIF delays are whole hundredths of a second, so a
// 60 fps scene plays at 50). FPS is the scene's frame rate, 1/frame_dt. The frames
// arrive top row first, as the PNGs are written (record::Recorder flips GL's bottom-up rows).
//
// ffmpeg runs in its own process group, so a Ctrl-C at the terminal reaches only ranryu, which
// finishes its frames, closes the pipe and waits for ffmpeg to finish the file (frame/stop.h). Its
// messages go to a temporary file; when it fails, finish() reports its exit status and its last
// message. SIGPIPE is ignored from the first VideoEncoder on, so that an ffmpeg that dies mid-run
// shows as a failed write, not as the end of ranryu.
#include <sys/types.h>

#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace ranryu::record {

enum class VideoFormat { mp4, webm, gif };

// What --video FILE asks for, checked before any work (VideoPlan::check).
struct VideoPlan {
    std::filesystem::path file;
    VideoFormat format = VideoFormat::mp4;
    std::filesystem::path ffmpeg;   // the executable found on PATH

    // The extension (.mp4, .webm, .gif), ffmpeg on PATH, and an existing FILE (refused unless
    // `force`). Throws InputError (exit 2) naming --video and the problem; creates and removes nothing.
    static VideoPlan check(const std::filesystem::path& file, bool force);
    // Makes FILE's folder if missing, removes an earlier FILE (check() let it through only with
    // --force), and checks that FILE can be created there. Throws InputError naming FILE.
    void prepare() const;
    const char* codec() const;   // "libx264", "libvpx-vp9", "gif"
};

// The executable `name` in a folder of $PATH, or empty.
std::filesystem::path find_on_path(const std::string& name);
// ffmpeg's -r for frames of `frame_dt` seconds: "50", "59.94".
std::string frame_rate(double frame_dt);

class VideoEncoder {
public:
    // Starts ffmpeg. Throws ranryu::Error when it cannot be started.
    VideoEncoder(const VideoPlan& plan, int width, int height, double frame_dt);
    ~VideoEncoder();   // finish() if not called, reporting nothing
    VideoEncoder(const VideoEncoder&) = delete;
    VideoEncoder& operator=(const VideoEncoder&) = delete;

    // The number of the video's first frame (a run resumed from a checkpoint: frame/checkpoint.h).
    // Before any write().
    void start_at(std::uint64_t frame);
    // Frame `frame` (width·height RGBA, top row first) to ffmpeg. Any thread; frames reach ffmpeg in
    // frame order from start_at()'s (0 by default): a call waits until every earlier frame has been written. After ffmpeg has
    // stopped reading (or abandon()) it does nothing, and finish() reports why.
    void write(std::uint64_t frame, const std::uint8_t* rgba);
    // A frame that will never come (its readback failed): the video is broken; no write waits for it.
    void abandon(std::uint64_t frame);
    // Closes the pipe and waits for ffmpeg to finish the file. Throws ranryu::Error with ffmpeg's exit
    // status and last message when it failed, or when frames were lost. Idempotent.
    void finish();

    std::uint64_t frames_written() const;
    const std::vector<std::string>& arguments() const { return argv_; }   // ffmpeg's argv

private:
    void close_and_wait();
    std::string stderr_tail();

    VideoPlan plan_;
    std::size_t bytes_;   // of one frame
    std::vector<std::string> argv_;
    pid_t pid_ = -1;
    int fd_ = -1;              // the pipe's write end
    std::FILE* err_ = nullptr; // ffmpeg's stderr (an unlinked temporary file)
    int status_ = 0;           // waitpid's, once waited

    mutable std::mutex mutex_;
    std::condition_variable turn_;
    std::uint64_t next_ = 0;      // the frame whose turn it is
    std::uint64_t written_ = 0;
    std::string broken_;          // why frames stopped reaching ffmpeg; empty while they do
    bool finished_ = false;
};

}  // namespace ranryu::record
