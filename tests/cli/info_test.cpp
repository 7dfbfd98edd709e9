// ranryu --version, --help, COMMAND --help and `ranryu scenes`: exit 0, print to stdout only, and
// say what they should.
#include <catch2/catch.hpp>

#include <regex>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

TEST_CASE("ranryu --version prints the version", "[cli][info]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"--version"});
    INFO(r.describe());
    CHECK(r.exit_code == 0);
    CHECK(r.err.empty());
    CHECK(std::regex_match(r.out, std::regex(R"(ranryu \d+\.\d+\.\d+\n)")));
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
        {"record", {"--frames", "--out", "--force"}},
        {"profile", {"--frames", "--warmup", "--json", "--csv"}},
        {"scenes", {}},
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
