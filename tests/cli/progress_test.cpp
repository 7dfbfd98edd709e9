// The progress line of record, profile and validate (engine/frame/progress.h): on a terminal one line
// rewritten in place with frame i/N, simulated time, fps, substeps a frame and ETA, erased at the end;
// elsewhere a plain line every RANRYU_PROGRESS_SECONDS (10 s by default); none with --quiet; always
// on stderr, so stdout stays the command's result.
#include <catch2/catch.hpp>

#include <optional>
#include <regex>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

RunOptions in(const fs::path& cwd) {
    RunOptions opt;
    opt.cwd = cwd;
    return opt;
}

// One progress line, parsed: "LABEL: frame I/N, t T s, F fps, S substeps/frame, ETA E".
struct Line {
    std::uint64_t frame = 0, total = 0;
    std::string time, fps, substeps, eta;   // "-" while not known
};

std::optional<Line> parse_line(const std::string& text, const std::string& label) {
    static const std::regex form(R"(: frame (\d+)/(\d+), t (\d+\.\d{3}|-) s, (\d+(?:\.\d)?|-) fps, (\d+|-) substeps/frame, ETA (\d+:\d\d(?::\d\d)?|-))");
    std::smatch m;
    if (!text.starts_with(label) || !std::regex_match(text.begin() + std::ptrdiff_t(label.size()), text.end(), m, form))
        return std::nullopt;
    return Line{std::stoull(m[1]), std::stoull(m[2]), m[3], m[4], m[5], m[6]};
}

// The pieces of `text` between '\r' and '\n'.
std::vector<std::string> pieces(const std::string& text) {
    std::vector<std::string> out;
    std::string piece;
    for (const char c : text) {
        if (c == '\r' || c == '\n') out.push_back(std::move(piece)), piece.clear();
        else piece += c;
    }
    out.push_back(piece);
    return out;
}

std::string rtrim(std::string s) {
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

}  // namespace

TEST_CASE("progress: on a terminal record rewrites one line in place with frame i/N, t, fps, substeps and ETA, then erases it",
          "[cli][progress]") {
    TempDir tmp;
    // An SPH scene: its substeps and simulated time come from the records that come back frames late.
    const int frames = 12;
    const Result r = run_in_terminal({kBin, "record", "--scene", scene_file("jet-at-box.json").string(), "--shading", "particles",
                                      "--size", "64x48", "--frames", std::to_string(frames), "--out", "out"},
                                     in(tmp.path()));
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);

    // Each line starts at a '\r' and is padded over the one before; none ends in '\n' (no scrolling).
    std::vector<Line> lines;
    for (const std::string& piece : pieces(r.out)) {
        if (!piece.starts_with("ranryu record:")) continue;
        INFO("line \"" << piece << "\"");
        const auto line = parse_line(rtrim(piece), "ranryu record");
        REQUIRE(line);
        CHECK(line->total == std::uint64_t(frames));
        lines.push_back(*line);
    }
    REQUIRE(!lines.empty());
    CHECK_FALSE(std::regex_search(r.out, std::regex("ranryu record: [^\r\n]*\n")));
    for (std::size_t i = 1; i < lines.size(); ++i) CHECK(lines[i].frame > lines[i - 1].frame);
    CHECK(lines.front().frame == 1);   // shown at once on a terminal

    // The last frame is always shown, with everything known by then.
    const Line& last = lines.back();
    CHECK(last.frame == std::uint64_t(frames));
    REQUIRE(last.time != "-");
    CHECK(std::stod(last.time) > 0.0);
    CHECK(std::stod(last.time) <= frames * 0.016666667 + 1e-3);   // as of a record, frames late
    REQUIRE(last.fps != "-");
    CHECK(std::stod(last.fps) > 0.0);
    REQUIRE(last.substeps != "-");
    CHECK(std::stoi(last.substeps) >= 1);
    CHECK(last.eta == "0:00");

    // Erased before the command's own output: "wrote ..." starts on a clean line.
    CHECK(std::regex_search(r.out, std::regex("ETA 0:00 *\r +\rwrote 12 frames")));
}

TEST_CASE("progress: on a narrow terminal the line is cut to its width", "[cli][progress]") {
    TempDir tmp;
    const int columns = 40;
    const Result r = run_in_terminal({kBin, "record", "--scene", scene_file("small.json").string(), "--frames", "3", "--out", "out"},
                                     in(tmp.path()), columns);
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    bool seen = false;
    for (const std::string& piece : pieces(r.out)) {
        if (!piece.starts_with("ranryu record:")) continue;
        seen = true;
        CHECK(piece.size() < std::size_t(columns));   // a wrapped line could not be rewritten in place
    }
    CHECK(seen);
}

TEST_CASE("progress: not on a terminal, a plain line every RANRYU_PROGRESS_SECONDS on stderr, and none with --quiet",
          "[cli][progress]") {
    TempDir tmp;
    const std::vector<std::string> args = {"profile", "--scene", scene_file("small.json").string(), "--warmup", "2", "--frames", "4"};
    RunOptions every_frame;
    every_frame.set_env = {{"RANRYU_PROGRESS_SECONDS", "0"}};

    const Result r = run_ranryu(tmp.path(), args, every_frame);
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find('\r') == std::string::npos);
    const auto lines = r.err_lines();
    REQUIRE(lines.size() == 6);   // warm-up included: frame i/6
    for (std::size_t i = 0; i < lines.size(); ++i) {
        INFO("line \"" << lines[i] << "\"");
        const auto line = parse_line(lines[i], "ranryu profile");
        REQUIRE(line);
        CHECK(line->frame == i + 1);
        CHECK(line->total == 6);
        CHECK(line->time != "-");           // the ballistic scene: frames x frame_dt
        CHECK(line->substeps == "4");       // small.json: 0.02 s frames of 0.005 s substeps
    }
    CHECK_THAT(r.out, !Contains("frame 1/6"));   // stdout keeps only the report

    const Result quiet = run_ranryu(tmp.path(), [&] {
        auto a = args;
        a.push_back("--quiet");
        return a;
    }(), every_frame);
    INFO(quiet.describe());
    REQUIRE(quiet.exit_code == 0);
    CHECK(quiet.err.empty());
    CHECK(quiet.out_lines().size() == r.out_lines().size());

    // By default a line every 10 s: a run this short shows none.
    RunOptions by_default;
    by_default.unset_env = {"RANRYU_PROGRESS_SECONDS"};
    const Result plain = run_ranryu(tmp.path(), args, by_default);
    INFO(plain.describe());
    REQUIRE(plain.exit_code == 0);
    CHECK(plain.err.empty());
}

TEST_CASE("progress: validate shows it too, over the case's whole run", "[cli][progress]") {
    TempDir tmp;
    RunOptions every_frame;
    every_frame.set_env = {{"RANRYU_PROGRESS_SECONDS", "0"}};
    const Result r = run_ranryu(tmp.path(), {"validate", "dam-break", "--spacing", "0.05"}, every_frame);
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const auto lines = r.err_lines();
    REQUIRE(lines.size() >= 2);
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        INFO("line \"" << lines[i] << "\"");
        const auto line = parse_line(lines[i], "ranryu validate dam-break");
        REQUIRE(line);
        CHECK(line->frame == i + 1);
        total = line->total;
    }
    CHECK(total == lines.size());
    CHECK_THAT(r.out, Contains("surge front error"));
}

TEST_CASE("progress: RANRYU_PROGRESS_SECONDS that is not a number of seconds is bad input", "[cli][progress][bad-input]") {
    TempDir tmp;
    for (const std::string value : {"soon", "-1", "1e9", ""}) {
        RunOptions opt;
        opt.set_env = {{"RANRYU_PROGRESS_SECONDS", value}};
        const Result r = run_ranryu(tmp.path(), {"record", "--scene", scene_file("small.json").string(), "--frames", "1", "--out", "out"}, opt);
        INFO("RANRYU_PROGRESS_SECONDS=" << value << "\n" << r.describe());
        CHECK(r.exit_code == 2);
        REQUIRE(r.err_lines().size() == 1);
        CHECK_THAT(r.err, Contains("RANRYU_PROGRESS_SECONDS=" + value));
        CHECK(r.out.empty());
        CHECK_FALSE(fs::exists(tmp / "out"));
    }
}
