// `ranryu validate impact-pressure` and `obstacle-impact` end to end (app/validate.cpp): the table and
// the JSON at a coarse spacing (H/dx = 10, 1,000 particles), so the numbers are the command's plumbing,
// not the physics (tests/gl/validation_test.cpp bounds those); the chart script on that JSON; and the
// scenes each case refuses.
#include <catch2/catch.hpp>

#include <cmath>
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
        // The series: one sample a frame, at the frame's middle (DFSPH's pressure is the frame's mean:
        // T = (f + 1/2) frame_dt sqrt(g/H) for frame f from 0), to the experiment's last T (6.98), every
        // reading finite (a dry sensor reads 0).
        const auto& sim = s["simulation"];
        const double dT = std::sqrt(9.81 / 0.3) / 60.0;
        REQUIRE(sim.size() == std::size_t(std::ceil(6.982 / dT - 1e-9)));
        for (std::size_t f = 0; f < sim.size(); ++f) {
            CHECK(sim[f]["T"].get<double>() == Approx((double(f) + 0.5) * dT).epsilon(1e-6));
            CHECK(std::isfinite(sim[f]["p"].get<double>()));
        }
    }
    CHECK(j["sensors"][0]["onset_experiment"].get<double>() == Approx(2.427).margin(1e-9));
    CHECK(j["sensors"][0]["peak_experiment"].get<double>() == Approx(2.843).margin(1e-9));
    CHECK(j["sample_offset_frames"].get<double>() == 0.5);
    CHECK(j["face_x"].get<double>() == Approx(1.61));
    CHECK(j["window"][0].get<double>() == 3.0);
    CHECK(j["window"][1].get<double>() == 5.5);

    SECTION("PBF's samples at the frame's end: its Density.y is the last step's pressure") {
        const Result p = run_ranryu(dir.path(), {"validate", "impact-pressure", "--spacing", "0.05", "--solver", "pbf", "--json", "pbf.json", "--quiet"},
                                    slow);
        INFO(p.out << p.err);
        REQUIRE(p.exit_code == 0);
        const auto k = nlohmann::json::parse(read_file(dir / "pbf.json"));
        CHECK(k["sample_offset_frames"].get<double>() == 0.0);
        const double dT = std::sqrt(9.81 / 0.3) / 60.0;
        const auto& first = k["sensors"][0]["simulation"];
        REQUIRE(first.size() > 2);
        for (std::size_t f = 0; f < 3; ++f) CHECK(first[f]["T"].get<double>() == Approx(double(f + 1) * dT).epsilon(1e-6));
    }

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

TEST_CASE("validate impact-pressure and obstacle-impact: a scene whose column or face is not where the case needs it is refused",
          "[validate]") {
    TempDir dir;
    const std::string impact = (source_dir() / "media" / "validation" / "impact-pressure.json").string(),
                      obstacle = (source_dir() / "media" / "validation" / "obstacle-impact.json").string();
    // The box case's scene given to the wall case: its column stands at the far end, against the wall
    // the case would read (a probe inside the column would read its weight from the first frame).
    Result r = run_ranryu(dir.path(), {"validate", "impact-pressure", "--scene", obstacle, "--spacing", "0.1", "--quiet"});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("impact-pressure") && Contains("no obstacle"));
    // And the other way: no box to read.
    r = run_ranryu(dir.path(), {"validate", "obstacle-impact", "--scene", impact, "--spacing", "0.05", "--quiet"});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("obstacle-impact") && Contains("a box obstacle"));
    // A box case whose column lies on the near side of the box.
    std::string text = read_file(obstacle);
    auto replace = [&](const std::string& from, const std::string& to) {
        const auto at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    };
    replace("\"min\": [1.992, 0.0, 0.0], \"max\": [3.22, 0.55, 1.0]", "\"min\": [0.05, 0.0, 0.0], \"max\": [0.5, 0.55, 1.0]");
    std::ofstream(dir / "near.json") << text;
    r = run_ranryu(dir.path(), {"validate", "obstacle-impact", "--scene", (dir / "near.json").string(), "--spacing", "0.05", "--quiet"});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("must lie beyond the box's face"));
}
