// ranryu record --video FILE (engine/record/video.h): ffmpeg makes the video from the frames; ffprobe
// confirms its frame count and size. Bad input is refused before any work with exit code 2 and
// nothing written: ffmpeg missing, an unknown type, an existing file without --force, a path that
// cannot be written. ffmpeg failing mid-run is reported with its exit status; an interrupted record
// still closes the video whole.
#include <catch2/catch.hpp>

#include <csignal>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

// ffmpeg and ffprobe are runtime options; the tests need both (scripts/install-deps.sh installs them).
bool have_ffmpeg() {
    if (on_path("ffmpeg") && on_path("ffprobe")) return true;
    if (env_is("RANRYU_REQUIRE_FFMPEG", "1")) {
        FAIL("ffmpeg or ffprobe is not on PATH, and RANRYU_REQUIRE_FFMPEG=1 requires the video tests");
        return false;
    }
    WARN("skipped: ffmpeg or ffprobe is not on PATH (scripts/install-deps.sh installs them; "
         "RANRYU_REQUIRE_FFMPEG=1 makes this a failure)");
    return false;
}

// "width,height,frames" of the first video stream, frames counted by decoding them all.
std::string probe(const fs::path& video) {
    const Result r = run({"ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                          "stream=nb_read_frames,width,height", "-of", "csv=p=0", video.string()});
    INFO(r.describe());
    CHECK(r.exit_code == 0);
    std::string s = r.out;
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ',')) s.pop_back();
    return s;
}

Result record(const TempDir& tmp, std::vector<std::string> extra, RunOptions opt = {}) {
    std::vector<std::string> args = {"record", "--scene", scene_file("small.json").string(), "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_ranryu(tmp.path(), args, opt);
}

std::size_t pngs_in(const fs::path& dir) {
    std::size_t n = 0;
    if (fs::is_directory(dir))
        for (const std::string& name : list_dir(dir)) n += name.ends_with(".png");
    return n;
}

}  // namespace

TEST_CASE("ranryu record --video makes an mp4 and a gif of every frame at the asked size", "[cli][record][video]") {
    if (!have_ffmpeg()) return;
    TempDir tmp;
    SECTION("mp4 (H.264) beside the PNGs") {
        const Result r = record(tmp, {"--size", "64x48", "--frames", "5", "--out", "out", "--video", "out/clip.mp4"});
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        CHECK_THAT(r.out, Contains("wrote 5 frames (64x48)") && Contains("wrote the video out/clip.mp4 (5 frames, libx264, 50 fps)"));
        CHECK(probe(tmp / "out" / "clip.mp4") == "64,48,5");
        CHECK(pngs_in(tmp / "out") == 5);
        const nlohmann::json run = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
        INFO(run.dump(2));
        CHECK(run["video"]["file"] == "out/clip.mp4");
        CHECK(run["video"]["codec"] == "libx264");
        CHECK(run["video"]["frame_rate"] == "50");   // small.json: frame_dt 0.02 s
        CHECK(run["video"]["frames"] == 5);
        CHECK(run["frames_written"] == 5);
    }
    SECTION("gif without the PNGs, at an odd size") {
        const Result r = record(tmp, {"--size", "63x47", "--frames", "4", "--out", "out", "--video", "clip.gif", "--no-png"});
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        CHECK(probe(tmp / "clip.gif") == "63,47,4");
        CHECK(list_dir(tmp / "out") == std::vector<std::string>{"run.json"});
        const nlohmann::json run = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
        CHECK(run["frames_written"] == 0);
        CHECK(run["frame_pattern"].is_null());
        CHECK(run["video"]["frames"] == 4);
    }
    SECTION("mp4 at an odd size is padded to even (yuv420p)") {
        const Result r = record(tmp, {"--size", "63x47", "--frames", "3", "--out", "out", "--video", "odd.mp4", "--no-png"});
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        CHECK(probe(tmp / "odd.mp4") == "64,48,3");
    }
}

TEST_CASE("ranryu record --video without ffmpeg on PATH: exit 2 naming ffmpeg, before any work", "[cli][record][video]") {
    TempDir tmp;
    fs::create_directory(tmp / "empty-bin");
    RunOptions opt;
    opt.set_env = {{"PATH", (tmp / "empty-bin").string()}};
    const Result r = record(tmp, {"--frames", "2", "--out", "out", "--video", "clip.mp4"}, opt);
    INFO(r.describe());
    CHECK(r.exit_code == 2);
    REQUIRE(r.err_lines().size() == 1);
    CHECK_THAT(r.err, Contains("--video clip.mp4") && Contains("ffmpeg is not installed"));
    CHECK(r.out.empty());   // not even the device line: no GPU work
    CHECK(list_dir(tmp.path()) == std::vector<std::string>{"empty-bin"});
}

TEST_CASE("ranryu record --video: bad file names and existing files are refused with exit 2", "[cli][record][video]") {
    if (!have_ffmpeg()) return;
    TempDir tmp;
    SECTION("an unknown type") {
        const Result r = record(tmp, {"--frames", "2", "--out", "out", "--video", "clip.avi"});
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains("--video clip.avi") && Contains(".mp4") && Contains(".webm") && Contains(".gif"));
        CHECK(list_dir(tmp.path()).empty());
    }
    SECTION("an existing file, kept as it was; --force replaces it") {
        write_file(tmp / "clip.mp4", "mine\n");
        const Result r = record(tmp, {"--frames", "2", "--out", "out", "--video", "clip.mp4"});
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        REQUIRE(r.err_lines().size() == 1);
        CHECK_THAT(r.err, Contains("--video clip.mp4") && Contains("exists") && Contains("--force"));
        CHECK(r.out.empty());
        CHECK(read_file(tmp / "clip.mp4") == "mine\n");
        CHECK(!fs::exists(tmp / "out"));

        const Result f = record(tmp, {"--frames", "2", "--size", "32x32", "--out", "out", "--video", "clip.mp4", "--force"});
        INFO(f.describe());
        REQUIRE(f.exit_code == 0);
        CHECK(probe(tmp / "clip.mp4") == "32,32,2");
    }
    SECTION("a path that cannot be written") {
        write_file(tmp / "a-file", "not a folder\n");
        const Result r = record(tmp, {"--frames", "2", "--out", "out", "--video", "a-file/clip.mp4"});
        INFO(r.describe());
        CHECK(r.exit_code == 2);
        REQUIRE(r.err_lines().size() == 1);
        CHECK_THAT(r.err, Contains("--video a-file/clip.mp4") && Contains("cannot"));
        CHECK(r.out.empty());
        CHECK(!fs::exists(tmp / "out"));
    }
}

TEST_CASE("ranryu record --video: ffmpeg failing mid-run is reported with its exit status", "[cli][record][video]") {
    TempDir tmp;
    // A stand-in that takes part of the first frames, says why it gives up, and exits 3.
    fs::create_directory(tmp / "bin");
    write_file(tmp / "bin" / "ffmpeg", "#!/bin/sh\nhead -c 20000 >/dev/null\necho 'stand-in ffmpeg: disk full' >&2\nexit 3\n");
    fs::permissions(tmp / "bin" / "ffmpeg", fs::perms::owner_all);
    RunOptions opt;
    opt.set_env = {{"PATH", (tmp / "bin").string() + ":/usr/bin:/bin"}};
    const Result r = record(tmp, {"--size", "64x48", "--frames", "6", "--out", "out", "--video", "clip.mp4"}, opt);
    INFO(r.describe());
    CHECK(r.exit_code == 1);
    REQUIRE(r.err_lines().size() == 1);
    CHECK_THAT(r.err, Contains("--video clip.mp4") && Contains("exit status 3") && Contains("stand-in ffmpeg: disk full"));
    CHECK(pngs_in(tmp / "out") == 6);   // the PNGs are not lost with the video
}

TEST_CASE("ranryu record --video interrupted by SIGINT still closes a whole video of every frame written",
          "[cli][record][video][interrupt]") {
    if (!have_ffmpeg()) return;
    TempDir tmp;
    Child child = start_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--size", "64x48",
                                            "--frames", "1000000", "--out", "out", "--video", "clip.mp4", "--quiet"});
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (pngs_in(tmp / "out") < 3 && std::chrono::steady_clock::now() < end)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    kill(child.pid, SIGINT);
    const Result r = wait(child);
    INFO(r.describe());
    REQUIRE(r.exit_code == 130);
    const nlohmann::json run = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
    INFO(run.dump(2));
    CHECK(run["interrupted"] == true);
    const auto frames = run["frames_written"].get<std::uint64_t>();
    CHECK(frames >= 3);
    CHECK(run["video"]["frames"] == frames);
    CHECK(probe(tmp / "clip.mp4") == "64,48," + std::to_string(frames));
}
