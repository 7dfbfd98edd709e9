// `ranryu validate impact-pressure` end to end (app/validate.cpp): its table and its JSON, at a coarse
// spacing (H/dx = 10, 2,160 particles), so the numbers are the command's plumbing, not the physics
// (tests/gl/validation_test.cpp bounds those).
#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

TEST_CASE("validate impact-pressure: the three sensors' table and series, against the experiment's data", "[validate]") {
    TempDir dir;
    RunOptions slow;
    slow.timeout = std::chrono::seconds(300);
    const Result r = run_ranryu(dir.path(), {"validate", "impact-pressure", "--spacing", "0.03", "--json", "ip.json", "--quiet"}, slow);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("Lobovsky et al. 2014"));
    for (const char* s : {"    P1      3.0 ", "    P3     30.0 ", "    P4     80.0 "}) CHECK_THAT(r.out, Contains(s));

    const auto j = nlohmann::json::parse(read_file(dir / "ip.json"));
    CHECK(j["case"] == "impact-pressure");
    CHECK(j["solver"] == "dfsph");
    CHECK(j["particles"].get<int>() == 20 * 10 * 5);   // the 0.6 x 0.3 x 0.15 m block at 0.03 m
    CHECK(j["height"].get<double>() == Approx(0.3));
    REQUIRE(j["sensors"].size() == 3);
    // The experiment's first readings past 0.25 (media/validation/lobovsky_exp_data_p{1,3,4}.csv, linear
    // between its samples): P1 (2.427, 0.173) -> (2.427, 0.364); P3 and P4 as the files give them.
    const char* names[] = {"P1", "P3", "P4"};
    const double heights[] = {0.003, 0.030, 0.080};
    for (std::size_t k = 0; k < 3; ++k) {
        const auto& s = j["sensors"][k];
        INFO(s.dump().substr(0, 400));
        CHECK(s["name"] == names[k]);
        CHECK(s["z"].get<double>() == Approx(heights[k]));
        CHECK(s["window_compared"].get<int>() > 5);
        REQUIRE(s["onset_experiment"].is_number());
        // The series: one sample a frame (T = frame t sqrt(g/H)), to the experiment's last T (6.98),
        // every reading finite (a dry sensor reads 0).
        const auto& sim = s["simulation"];
        const double dT = std::sqrt(9.81 / 0.3) / 60.0;
        REQUIRE(sim.size() == std::size_t(std::ceil(6.982 / dT - 1e-9)));
        for (std::size_t f = 0; f < sim.size(); ++f) {
            CHECK(sim[f]["T"].get<double>() == Approx(double(f + 1) * dT).epsilon(1e-6));
            CHECK(std::isfinite(sim[f]["p"].get<double>()));
        }
    }
    CHECK(j["sensors"][0]["onset_experiment"].get<double>() == Approx(2.427).margin(1e-9));
    CHECK(j["sensors"][0]["peak_experiment"].get<double>() == Approx(2.843).margin(1e-9));
    CHECK(j["window"][0].get<double>() == 3.0);
    CHECK(j["window"][1].get<double>() == 5.5);

    SECTION("its chart: PNG and SVG, with the axes' and legend's labels as text") {
        // matplotlib is a runtime option of the chart script (scripts/install-deps.sh installs it).
        if (run({"/usr/bin/python3", "-c", "import matplotlib"}).exit_code != 0) {
            if (env_is("RANRYU_REQUIRE_MATPLOTLIB", "1")) FAIL("python3-matplotlib is missing, and RANRYU_REQUIRE_MATPLOTLIB=1 requires the charts");
            WARN("skipped: python3-matplotlib is missing (RANRYU_REQUIRE_MATPLOTLIB=1 makes this a failure)");
            return;
        }
        const fs::path prefix = dir.path() / "charts" / "impact";
        const Result c = run({"/usr/bin/python3", (source_dir() / "scripts" / "impact-charts.py").string(), (dir / "ip.json").string(), "--out",
                              prefix.string()});
        INFO(c.out << c.err);
        REQUIRE(c.exit_code == 0);
        for (const char* ext : {".png", ".svg"}) {
            const fs::path f = prefix.string() + ext;
            INFO(f);
            REQUIRE(fs::exists(f));
            CHECK(fs::file_size(f) > 5000);
        }
        CHECK(read_file(prefix.string() + ".png").substr(1, 3) == "PNG");
        const std::string svg = read_file(prefix.string() + ".svg");
        for (const char* label : {"p/(rho0 g H)", "T = t sqrt(g/H)", "P1, 3 mm above the floor", "P3, 30 mm above the floor",
                                  "P4, 80 mm above the floor", "experiment (Lobovsky et al. 2014)", "dfsph, nu_b 0.001, H/dx 10",
                                  "compared window"})
            CHECK_THAT(svg, Contains(label));
        // Anything but the case's JSON is refused, naming the file.
        std::ofstream(dir / "other.json") << R"({"case": "dam-break"})";
        const Result bad = run({"/usr/bin/python3", (source_dir() / "scripts" / "impact-charts.py").string(), (dir / "other.json").string(),
                                "--out", prefix.string()});
        CHECK(bad.exit_code != 0);
        CHECK_THAT(bad.err, Contains("other.json") && Contains("not the JSON of `ranryu validate impact-pressure` or `obstacle-impact`"));
    }
}
