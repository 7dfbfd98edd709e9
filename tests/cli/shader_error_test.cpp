// A shader that fails to compile: ranryu exits 1 and stderr names the file and the line of the
// error (through the #include step's #line bookkeeping) and carries the driver's log.
//
// Each case copies the repository's glsl/ tree into a temporary folder, breaks one line of one file
// there and runs `ranryu profile --shader-dir COPY`. The broken line is placed relative to a marker
// line of the file, so the expected line number follows the file as it is edited.
#include <catch2/catch.hpp>

#include <regex>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

const std::string kBroken = "int ranryu_injected_error = ;   // injected by tests/cli/shader_error_test.cpp";

std::vector<std::string> read_lines(const fs::path& p) { return Result::split_lines(read_file(p)); }

void write_lines(const fs::path& p, const std::vector<std::string>& lines) {
    std::string text;
    for (const std::string& l : lines) text += l + "\n";
    write_file(p, text);
}

// Inserts `text` (default kBroken) after the first line of `file` that contains `marker` (or before
// the last such line, if `before_last`). Returns the 1-based line number of the inserted line.
int inject(const fs::path& file, const std::string& marker, bool before_last = false, const std::string& text = kBroken) {
    std::vector<std::string> lines = read_lines(file);
    int at = -1;
    for (int i = 0; i < int(lines.size()); ++i)
        if (lines[std::size_t(i)].find(marker) != std::string::npos) {
            at = i;
            if (!before_last) break;
        }
    if (at < 0) throw std::runtime_error(file.string() + ": no line with \"" + marker + "\" to inject after");
    const int index = before_last ? at : at + 1;   // 0-based position of the new line
    lines.insert(lines.begin() + index, text);
    write_lines(file, lines);
    return index + 1;
}

fs::path copy_glsl(const TempDir& tmp) {
    const fs::path dst = tmp / "glsl";
    REQUIRE(fs::is_directory(glsl_dir()));
    fs::copy(glsl_dir(), dst, fs::copy_options::recursive);
    return dst;
}

Result profile_with(const TempDir& tmp, const fs::path& shader_dir) {
    return run_ranryu(tmp.path(), {"profile", "--shader-dir", shader_dir.string(), "--scene", scene_file("small.json").string(),
                                   "--size", "64x48", "--frames", "1", "--warmup", "0"});
}

// ranryu's report of a compile error at `file`:`line`: exit code 1; a "ranryu: ..." line naming
// file:line; the driver's log, its locations rewritten to file:line:..., with an error at that line;
// and no other line of `file` blamed (a wrong #line mapping would name another).
void check_compile_error(const Result& r, const std::string& file, int line) {
    INFO(r.describe());
    const std::string at = file + ":" + std::to_string(line) + ":";
    INFO("expected location " << at);
    CHECK(r.exit_code == 1);
    bool summary = false, log = false;
    for (const std::string& l : r.err_lines()) {
        if (l.starts_with("ranryu:") && l.find(at) != std::string::npos) summary = true;
        if (l.starts_with(at) && l.find("error") != std::string::npos) log = true;   // the driver's log, annotated
    }
    CHECK(summary);
    CHECK(log);
    const std::regex any_line_of_file(std::regex_replace(file, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") + R"(:(\d+):)");
    for (std::sregex_iterator it(r.err.begin(), r.err.end(), any_line_of_file), end; it != end; ++it) {
        INFO("stderr names " << (*it)[0].str());
        CHECK((*it)[1].str() == std::to_string(line));
    }
}

}  // namespace

TEST_CASE("shader errors: an untouched copy of glsl/ given with --shader-dir compiles and runs", "[cli][shader]") {
    // The control for the cases below: the copy itself is fine, so their failures are the injected lines.
    TempDir tmp;
    const Result r = profile_with(tmp, copy_glsl(tmp));
    INFO(r.describe());
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("ballistic.integrate"));
}

TEST_CASE("shader errors: a compile error names the file and line and includes the driver log", "[cli][shader]") {
    TempDir tmp;
    const fs::path glsl = copy_glsl(tmp);

    SECTION("in the compute shader itself, after its #include") {
        const int line = inject(glsl / "sim/integrate.comp", "void main()");
        check_compile_error(profile_with(tmp, glsl), "sim/integrate.comp", line);
    }
    SECTION("in a file the compute shader includes") {
        // Before the include guard's closing #endif: GLSL sees it (C++-only parts end earlier).
        const int line = inject(glsl / "shared/bindings.h", "#endif", /*before_last=*/true);
        check_compile_error(profile_with(tmp, glsl), "shared/bindings.h", line);
    }
    SECTION("in a file that a render shader includes, after that file's own #include") {
        const int line = inject(glsl / "common/frame.glsl", "uniform FrameBlock");
        check_compile_error(profile_with(tmp, glsl), "common/frame.glsl", line);
    }
    SECTION("in a render shader, after an include that includes another file") {
        const int line = inject(glsl / "render/impostor.frag", "void main()");
        check_compile_error(profile_with(tmp, glsl), "render/impostor.frag", line);
    }
    SECTION("in the compute shader, with comment lines before #version") {
        const fs::path file = glsl / "sim/integrate.comp";
        std::vector<std::string> lines = read_lines(file);
        lines.insert(lines.begin(), {"// a comment before #version", "// and another"});
        write_lines(file, lines);
        const int line = inject(file, "void main()");
        check_compile_error(profile_with(tmp, glsl), "sim/integrate.comp", line);
    }
}

TEST_CASE("shader errors: the report is the summary and the driver's errors, not its warnings", "[cli][shader]") {
    // An undeclared name where a pass's sums are set up: Mesa then also warns of every variable left
    // uninitialised after it, a dozen lines. The report keeps the errors (at most four) and counts the rest.
    TempDir tmp;
    const fs::path glsl = copy_glsl(tmp);
    const int line = inject(glsl / "sim/dfsph/compute_density.comp", "        xi_ = position[i].xyz;", false,
                            "        xi_ = ranryu_injected_undeclared[i].xyz;");
    const Result r = run_ranryu(tmp.path(), {"profile", "--shader-dir", glsl.string(), "--scene", "dam-break", "--spacing", "0.04",
                                             "--frames", "1", "--warmup", "0", "--size", "32x32", "--quiet"});
    INFO(r.describe());
    CHECK(r.exit_code == 1);
    const std::vector<std::string> lines = r.err_lines();
    REQUIRE_FALSE(lines.empty());
    CHECK_THAT(lines.front(), Contains("sim/dfsph/compute_density.comp:" + std::to_string(line) + ":"));
    CHECK(lines.size() <= 6);   // the summary, four of the driver's lines, how many more
    for (std::size_t k = 1; k < lines.size(); ++k)
        if (lines[k].starts_with("sim/")) CHECK_THAT(lines[k], Contains("error"));
}

TEST_CASE("shader errors: a missing include names the including file and line", "[cli][shader]") {
    // Only sim/integrate.comp includes the missing file, so the report does not depend on which
    // program the engine builds first.
    TempDir tmp;
    const fs::path glsl = copy_glsl(tmp);
    const int line = inject(glsl / "sim/integrate.comp", "#include", false, "#include \"no-such-file.glsl\"");
    const Result r = profile_with(tmp, glsl);
    INFO(r.describe());
    CHECK(r.exit_code == 1);
    REQUIRE(r.err_lines().size() == 1);
    CHECK_THAT(r.err, Contains("sim/integrate.comp:" + std::to_string(line) + ":"));
    CHECK_THAT(r.err, Contains("no-such-file.glsl"));
}

TEST_CASE("shader errors: --shader-dir that is not a folder is bad input", "[cli][shader][bad-input]") {
    TempDir tmp;
    const std::string dir = tmp.str("no-such-folder");
    const Result r = run_ranryu(tmp.path(), {"profile", "--shader-dir", dir, "--scene", scene_file("small.json").string(),
                                             "--frames", "1", "--warmup", "0"});
    INFO(r.describe());
    CHECK(r.exit_code == 2);
    // The device line may be printed before the folder is looked at; the error is one line.
    REQUIRE(r.err_lines().size() == 1);
    CHECK_THAT(r.err, Contains("--shader-dir " + dir));
}
