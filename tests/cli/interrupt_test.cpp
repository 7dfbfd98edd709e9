// SIGINT and SIGTERM stop a run at a frame boundary (engine/frame/stop.h): exit code 130 with one
// line naming the signal; record writes every frame it ran, each a whole PNG, and run.json saying it
// was interrupted and at which frame.
#include <catch2/catch.hpp>

#include <csignal>
#include <regex>

#include <nlohmann/json.hpp>

#include "image.h"
#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

std::vector<std::string> pngs_in(const fs::path& dir) {
    std::vector<std::string> names;
    if (!fs::is_directory(dir)) return names;
    for (const std::string& name : list_dir(dir))
        if (name.ends_with(".png")) names.push_back(name);
    return names;
}

// Polls until `done` holds or `limit` passes; says whether it held.
template <class F>
bool wait_until(F done, std::chrono::seconds limit = std::chrono::seconds(60)) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (!done()) {
        if (std::chrono::steady_clock::now() > end) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
}

// Starts `record` of a million frames of `scene`, signals it once a few frames are on disk, and
// checks what it leaves.
void check_interrupted_record(const std::string& scene, const std::vector<std::string>& extra, int signal, const std::string& name) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    const std::uint64_t asked = 1'000'000;
    std::vector<std::string> args = {"record", "--scene", scene_file(scene).string(), "--size", "64x48",
                                     "--frames", std::to_string(asked), "--out", out.string(), "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    Child child = start_ranryu(tmp.path(), args);
    const bool started = wait_until([&] { return pngs_in(out).size() >= 3; });
    kill(child.pid, signal);
    const Result r = wait(child);
    INFO(r.describe());
    REQUIRE(started);

    CHECK(r.exit_code == 130);
    REQUIRE(r.err_lines().size() == 1);
    CHECK(std::regex_search(r.err, std::regex("^ranryu: interrupted by " + name + " after \\d+ of 1000000 frames\n$")));
    CHECK_THAT(r.out, Contains("wrote ") && Contains(" and run.json to "));

    const nlohmann::json run = nlohmann::json::parse(read_file(out / "run.json"));
    INFO(run.dump(2));
    CHECK(run["interrupted"] == true);
    REQUIRE(run["interrupted_at_frame"].is_number_unsigned());
    const auto at = run["interrupted_at_frame"].get<std::uint64_t>();
    CHECK(at >= 3);
    CHECK(at < asked);
    CHECK(run["frames"] == at);
    CHECK(run["frames_requested"] == asked);
    CHECK(run["frames_written"] == at);
    CHECK_FALSE(run.contains("instability"));
    CHECK_THAT(r.err, Contains("after " + std::to_string(at) + " of"));

    // Exactly frames 0 .. at-1, each whole, and nothing half-written (.tmp) beside them.
    std::vector<std::string> want;
    for (std::uint64_t f = 0; f < at; ++f) {
        char file[32];
        std::snprintf(file, sizeof file, "frame_%05llu.png", static_cast<unsigned long long>(f));
        want.push_back(file);
    }
    want.push_back("run.json");
    CHECK(list_dir(out) == want);
    for (const std::string& png : pngs_in(out)) check_whole_png(out / png, 64, 48);
}

// Waits for the progress line of `label`'s frame 3, sends each of `signals` 50 ms apart, and checks
// that the run stopped at a frame boundary: exit code 130, its last line naming the first signal.
Result interrupt_after_frame_3(Child& child, const std::string& label, const std::vector<int>& signals, const std::string& name) {
    const bool started = wait_until([&] { return child.err_so_far().find("ranryu " + label + ": frame 3/") != std::string::npos; });
    for (std::size_t k = 0; k < signals.size(); ++k) {
        if (k) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        kill(child.pid, signals[k]);
    }
    Result r = wait(child);
    INFO(r.describe());
    REQUIRE(started);
    CHECK(r.exit_code == 130);
    const auto lines = r.err_lines();
    REQUIRE(!lines.empty());
    CHECK(std::regex_match(lines.back(), std::regex("ranryu: interrupted by " + name + " after \\d+( of \\d+)? frames")));
    return r;
}

}  // namespace

TEST_CASE("interrupt: SIGINT stops record at a frame boundary with every frame written and run.json saying so",
          "[cli][interrupt]") {
    check_interrupted_record("small.json", {}, SIGINT, "SIGINT");
}

TEST_CASE("interrupt: SIGTERM stops an SPH record, whose frames wait for their records, the same way", "[cli][interrupt]") {
    // The gated path: frames captured but not yet validated when the signal comes are written too.
    check_interrupted_record("jet-at-box.json", {"--shading", "particles"}, SIGTERM, "SIGTERM");
}

TEST_CASE("interrupt: a record that is not interrupted says so in run.json", "[cli][interrupt]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--frames", "2", "--out", "out"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const nlohmann::json run = nlohmann::json::parse(read_file(tmp / "out" / "run.json"));
    CHECK(run["interrupted"] == false);
    CHECK(run["interrupted_at_frame"].is_null());
    CHECK(run["frames_requested"] == 2);
}

TEST_CASE("interrupt: SIGINT stops profile and validate with exit code 130 and one line", "[cli][interrupt]") {
    TempDir tmp;
    // The progress on stderr, every frame, shows the run is in its frame loop (handlers installed).
    RunOptions opt;
    opt.set_env = {{"RANRYU_PROGRESS_SECONDS", "0"}};
    const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
        {"profile", {"profile", "--scene", scene_file("small.json").string(), "--warmup", "0", "--frames", "1000000",
                     "--json", "profile.json"}},
        {"validate dam-break", {"validate", "dam-break", "--spacing", "0.02", "--json", "front.json"}},
    };
    for (const auto& [label, args] : runs) {
        Child child = start_ranryu(tmp.path(), args, opt);
        const Result r = interrupt_after_frame_3(child, label, {SIGINT}, "SIGINT");
        INFO(r.describe());
        const auto lines = r.err_lines();
        for (std::size_t i = 0; i + 1 < lines.size(); ++i) CHECK_THAT(lines[i], Contains("ranryu " + label + ": frame "));
        // No report of a run cut short.
        CHECK_FALSE(fs::exists(tmp / "profile.json"));
        CHECK_FALSE(fs::exists(tmp / "front.json"));
    }
}

TEST_CASE("interrupt: the same SIGTERM delivered twice at once, as timeout(1) sends it, still stops at a frame boundary "
          "with the records written",
          "[cli][interrupt]") {
    // timeout(1) signals the command and then its whole process group: the run sees SIGTERM twice,
    // microseconds apart. Until 2026-11-26 the second ended the process the default way (exit 143, no
    // records), when the first had been delivered before it; engine/frame/stop.h now takes a signal
    // within a second of the first as the same request. Here the second comes 50 ms after the first,
    // after its delivery, the case that lost the records.
    TempDir tmp;
    RunOptions opt;
    opt.set_env = {{"RANRYU_PROGRESS_SECONDS", "0"}};
    const fs::path records = tmp / "records.csv";
    Child child = start_ranryu(tmp.path(),
                               {"profile", "--scene", scene_file("jet-at-box.json").string(), "--shading", "particles", "--size",
                                "64x48", "--warmup", "0", "--frames", "1000000", "--records", records.string()},
                               opt);
    const Result r = interrupt_after_frame_3(child, "profile", {SIGTERM, SIGTERM}, "SIGTERM");
    INFO(r.describe());
    CHECK_THAT(r.err, Contains("after ") && Contains(" of 1000000 frames"));
    // The records of every frame run: a header and at least the three frames seen.
    REQUIRE(fs::exists(records));
    const std::string csv = read_file(records);
    CHECK(std::count(csv.begin(), csv.end(), '\n') >= 4);
    CHECK_THAT(csv, Contains("frame,time,substeps"));
}

TEST_CASE("interrupt: a second SIGTERM a second or more after the first ends the run at once", "[cli][interrupt]") {
    // engine/frame/stop.h: a second signal later than a second after the first is a second request, for
    // a run that will not come to a frame boundary. The dam break at spacing 0.006 (15k particles) takes
    // 3-14 s a frame on llvmpipe (measured 12-14 s for frames 3 and 4), so after frame 2's progress line
    // the first SIGTERM waits for a frame boundary seconds away, and the second, 1.2 s later, must end
    // the process the default way (killed by SIGTERM: 128 + 15) long before it.
    TempDir tmp;
    RunOptions opt;
    opt.set_env = {{"RANRYU_PROGRESS_SECONDS", "0"}};
    Child child = start_ranryu(tmp.path(),
                               {"profile", "--scene", "dam-break", "--spacing", "0.006", "--shading", "particles", "--size", "64x48",
                                "--warmup", "0", "--frames", "1000"},
                               opt);
    const bool started = wait_until([&] { return child.err_so_far().find("ranryu profile: frame 2/") != std::string::npos; });
    kill(child.pid, SIGTERM);
    std::this_thread::sleep_for(std::chrono::milliseconds(1200));
    // A device that runs these frames in well under a second (a GPU's) has reached the frame boundary
    // and reported its stop by now: the case needs a frame slower than that (llvmpipe's).
    const bool stopped_already = child.err_so_far().find("interrupted by") != std::string::npos;
    const auto second = std::chrono::steady_clock::now();
    kill(child.pid, SIGTERM);
    const Result r = wait(child);
    const double after = std::chrono::duration<double>(std::chrono::steady_clock::now() - second).count();
    INFO(r.describe() << "; ended " << after << " s after the second signal");
    REQUIRE(started);
    if (stopped_already) {
        WARN("skipped: the run stopped at a frame boundary within 1.2 s of the first signal, before the second was sent");
        return;
    }
    CHECK(r.exit_code == 128 + SIGTERM);
    CHECK(after < 2.0);
    CHECK_THAT(r.err, !Contains("interrupted by"));   // not the frame boundary's stop
}
