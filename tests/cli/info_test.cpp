// ranryu --version, --help, COMMAND --help and `ranryu scenes`: exit 0, print to stdout only, and
// say what they should.
#include <catch2/catch.hpp>

#include <algorithm>
#include <regex>

#include "run_helper.h"
#include "scene/scene.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

TEST_CASE("ranryu --version prints the version and the commit it was built from", "[cli][info]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"--version"});
    INFO(r.describe());
    CHECK(r.exit_code == 0);
    CHECK(r.err.empty());
    std::smatch m;
    REQUIRE(std::regex_match(r.out, m, std::regex(R"(ranryu \d+\.\d+\.\d+ \(commit ([0-9a-f]{40}(-dirty)?|unknown)\)\n)")));
    // Built from this checkout: a commit of its history (HEAD may have moved on since the build).
    if (fs::exists(source_dir() / ".git") && on_path("git")) {
        const std::string hash = m[1].str().substr(0, 40);
        const Result git = run({"git", "-C", source_dir().string(), "cat-file", "-e", hash + "^{commit}"});
        INFO(git.describe());
        CHECK(git.exit_code == 0);
    }
}

TEST_CASE("ranryu --version: the commit is \"unknown\" when built outside a git checkout", "[cli][info]") {
    // cmake/Commit.cmake, which the build runs, on a tarball's tree: no .git, or inside another checkout.
    TempDir tmp;
    const fs::path tarball = tmp / "ranryu-0.1.0";
    fs::create_directories(tarball);
    auto commit_of = [&](const fs::path& source, const std::string& git) {
        const fs::path out = tmp / "commit.cpp";
        const Result r = run({RANRYU_CMAKE, "-DSOURCE_DIR=" + source.string(), "-DOUTPUT=" + out.string(), "-DGIT=" + git, "-P",
                              (source_dir() / "cmake" / "Commit.cmake").string()});
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        std::smatch m;
        const std::string text = read_file(out);
        REQUIRE(std::regex_search(text, m, std::regex(R"re(return "([^"]*)";)re")));
        return m[1].str();
    };
    CHECK(commit_of(tarball, "") == "unknown");   // no git at all
    if (!on_path("git")) return;
    CHECK(commit_of(tarball, "git") == "unknown");
    // Unpacked inside a checkout of something else: that checkout's commit is not ours.
    const std::vector<std::string> git = {"git", "-C", tmp.path().string(), "-c", "user.name=t", "-c", "user.email=t@example.com",
                                        "-c", "commit.gpgsign=false"};
    auto git_run = [&](std::vector<std::string> args) {
        args.insert(args.begin(), git.begin(), git.end());
        const Result r = run(args);
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        return r.out;
    };
    git_run({"init", "-q"});
    write_file(tmp / "file.txt", "x\n");
    git_run({"add", "file.txt"});
    git_run({"commit", "-q", "-m", "other"});
    CHECK(commit_of(tarball, "git") == "unknown");
    // The top of a checkout: its commit, and "-dirty" once a tracked file changes.
    const std::string head = git_run({"rev-parse", "HEAD"}).substr(0, 40);
    CHECK(commit_of(tmp.path(), "git") == head);
    write_file(tmp / "file.txt", "y\n");
    CHECK(commit_of(tmp.path(), "git") == head + "-dirty");
}

TEST_CASE("ranryu --help lists every command and the exit codes", "[cli][info]") {
    TempDir tmp;
    for (const std::string flag : {"--help", "-h", "help"}) {
        const Result r = run_ranryu(tmp.path(), {flag});
        INFO(flag << "\n" << r.describe());
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        CHECK_THAT(r.out, StartsWith("ranryu"));
        for (const char* word : {"usage: ranryu COMMAND", "run", "record", "profile", "scenes", "--version", "exit codes"})
            CHECK_THAT(r.out, Contains(word));
    }
}

TEST_CASE("ranryu COMMAND --help mentions each option the command takes", "[cli][info]") {
    TempDir tmp;
    const std::vector<std::string> common = {"--scene", "--size", "--shader-dir", "--gl-debug"};
    const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
        {"run", {"--frames", "--screenshot"}},
        {"record", {"--frames", "--out", "--force", "--quiet"}},
        {"profile", {"--frames", "--warmup", "--json", "--csv", "--quiet"}},
        {"scenes", {"--schema", "--markdown"}},
    };
    for (const auto& [cmd, own] : commands) {
        const Result r = run_ranryu(tmp.path(), {cmd, "--help"});
        INFO("ranryu " << cmd << " --help\n" << r.describe());
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        CHECK_THAT(r.out, StartsWith("usage: ranryu " + cmd));
        if (cmd != "scenes")
            for (const std::string& opt : common) CHECK_THAT(r.out, Contains(opt));
        for (const std::string& opt : own) CHECK_THAT(r.out, Contains(opt));
    }
    // --help wins over the other options and does no work: no output folder appears.
    const Result r = run_ranryu(tmp.path(), {"record", "--out", tmp.str("never"), "--frames", "3", "--help"});
    INFO(r.describe());
    CHECK(r.exit_code == 0);
    CHECK_FALSE(fs::exists(tmp / "never"));
    CHECK(list_dir(tmp.path()).empty());
}

TEST_CASE("ranryu scenes lists the bundled scenes with descriptions", "[cli][info]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"scenes"});
    INFO(r.describe());
    CHECK(r.exit_code == 0);
    CHECK(r.err.empty());
    bool found = false;
    for (const std::string& line : r.out_lines())
        if (line.starts_with("falling-block ")) {
            found = true;
            // The description follows the name.
            CHECK(line.find_first_not_of(' ', std::string("falling-block").size()) != std::string::npos);
        }
    CHECK(found);
    // A scene whose file says why its settings are what they are (sph.why) has that on the next
    // line, and one without has none.
    const std::vector<std::string> lines = r.out_lines();
    for (const ranryu::scene::BundledScene& b : ranryu::scene::bundled()) {
        INFO(b.name);
        const auto at = std::find_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.starts_with(b.name + " "); });
        REQUIRE(at != lines.end());
        const bool has = at + 1 != lines.end() && (at + 1)->find("why its settings: ") != std::string::npos;
        CHECK(has == !b.why.empty());
        if (has) CHECK_THAT(*(at + 1), Contains(b.why));
    }
}

TEST_CASE("ranryu scenes --schema and --markdown print the committed scene schema and docs/SCENES.md", "[cli][info]") {
    // What `cmake --build build/test --target scene-docs` writes; tests/unit/scene_keys_test.cpp checks
    // the same text against the table in process.
    TempDir tmp;
    const std::pair<std::string, fs::path> outputs[] = {{"--schema", source_dir() / "media" / "scenes" / "scene.schema.json"},
                                                        {"--markdown", source_dir() / "docs" / "SCENES.md"}};
    for (const auto& [option, file] : outputs) {
        const Result r = run_ranryu(tmp.path(), {"scenes", option});
        INFO("ranryu scenes " << option << "\n" << r.describe());
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        CHECK(r.out == read_file(file));
    }
    CHECK(list_dir(tmp.path()).empty());
}

TEST_CASE("ranryu with no command exits 2 with one line on stderr", "[cli][info]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {});
    INFO(r.describe());
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    REQUIRE(r.err_lines().size() == 1);
    CHECK_THAT(r.err, Contains("no command"));
}
