// Resource limits (frame/memory.h): a scene the device has no room for is refused before anything is
// built or written, with its estimate and the finest spacing that fits; RANRYU_MEMORY_LIMIT_MB stands
// for a smaller device; `profile` prints the estimate next to what was allocated.
#include <catch2/catch.hpp>

#include <chrono>
#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

// The spacing the refusal suggests ("--spacing X"), or "" when there is none.
std::string suggested_spacing(const std::string& err) {
    std::smatch m;
    return std::regex_search(err, m, std::regex("the finest spacing that fits is --spacing ([0-9.e-]+)")) ? m[1].str() : "";
}

void check_refusal(const Result& r, const std::string& scene, const std::string& particles) {
    INFO(r.describe());
    CHECK(r.exit_code == 2);
    CHECK(r.err_lines().size() == 1);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Contains("scene " + scene));
    CHECK_THAT(r.err, Contains(particles + " particles need an estimated"));
    CHECK_THAT(r.err, Contains("MiB available"));
    CHECK_FALSE(suggested_spacing(r.err).empty());
}

}  // namespace

TEST_CASE("limits: the dam break at 64M particles is refused at once with its estimate, and nothing is written",
          "[cli][limits]") {
    TempDir tmp;
    const auto start = std::chrono::steady_clock::now();
    // 12 GiB of memory, whatever this machine has free: the estimate (15 GiB) exceeds it, so the
    // refusal is the memory one everywhere (it is checked before the dispatch limit, 8.4M particles on
    // llvmpipe, which tests/gl/memory_test.cpp tests).
    RunOptions as_ci;
    as_ci.set_env = {{"RANRYU_MEMORY_LIMIT_MB", "12288"}};
    const Result r = run_ranryu(tmp.path(), {"record", "--scene", "dam-break", "--spacing", "0.0005", "--out", tmp.str("out")}, as_ci);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    check_refusal(r, "dam-break", "64000000");
    CHECK(seconds < 20.0);   // no allocation, no shader build: it counts and answers
    CHECK_FALSE(fs::exists(tmp / "out"));
}

TEST_CASE("limits: RANRYU_MEMORY_LIMIT_MB refuses a normal scene, which runs at the spacing suggested", "[cli][limits]") {
    TempDir tmp;
    RunOptions small;
    small.set_env = {{"RANRYU_MEMORY_LIMIT_MB", "8"}};
    const std::vector<std::string> common = {"--scene", "dam-break", "--shading", "particles", "--size", "64x48", "--frames", "1"};
    std::vector<std::string> args = {"record", "--spacing", "0.004", "--out", tmp.str("refused")};
    args.insert(args.end(), common.begin(), common.end());
    const Result refused = run_ranryu(tmp.path(), args, small);
    check_refusal(refused, "dam-break", "125000");
    CHECK_THAT(refused.err, Contains("(RANRYU_MEMORY_LIMIT_MB)"));
    CHECK_FALSE(fs::exists(tmp / "refused"));

    const std::string spacing = suggested_spacing(refused.err);
    args = {"record", "--spacing", spacing, "--out", tmp.str("accepted")};
    args.insert(args.end(), common.begin(), common.end());
    const Result accepted = run_ranryu(tmp.path(), args, small);
    INFO(accepted.describe());
    REQUIRE(accepted.exit_code == 0);
    CHECK(fs::exists(tmp / "accepted" / "frame_00000.png"));
    // run.json keeps the estimate, what was allocated and the limit it was checked against.
    std::ifstream in(tmp / "accepted" / "run.json");
    const nlohmann::json run = nlohmann::json::parse(in);
    const auto& m = run.at("device_memory");
    CHECK(m.at("source") == "RANRYU_MEMORY_LIMIT_MB");
    CHECK(m.at("available_bytes").get<double>() == 8.0 * 1024 * 1024);
    CHECK(m.at("estimated_bytes").get<double>() <= 0.9 * 8.0 * 1024 * 1024);

    RunOptions bad;
    bad.set_env = {{"RANRYU_MEMORY_LIMIT_MB", "lots"}};
    const Result r = run_ranryu(tmp.path(), {"profile", "--scene", "drop", "--frames", "1"}, bad);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("RANRYU_MEMORY_LIMIT_MB=lots"));
}

TEST_CASE("limits: profile prints the memory estimate next to what was allocated, within 10 %", "[cli][limits][profile]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"profile", "--scene", "dam-break", "--spacing", "0.01", "--size", "64x48", "--frames", "1",
                                             "--warmup", "0", "--json", tmp.str("p.json")});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("device memory: estimated "));
    CHECK_THAT(r.out, Contains(" MiB, allocated "));
    std::ifstream in(tmp / "p.json");
    const nlohmann::json m = nlohmann::json::parse(in).at("device_memory");
    const double estimated = m.at("estimated_bytes").get<double>(), allocated = m.at("allocated_bytes").get<double>();
    CHECK(estimated >= 0.9 * allocated);
    CHECK(estimated <= 1.1 * allocated);
    CHECK(m.at("parts").contains("solver dfsph"));
}
