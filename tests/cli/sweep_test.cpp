// ranryu sweep (app/sweep.cpp) and its charts (scripts/sweep-charts.py): a tiny sweep's rows, a
// deliberately unstable setting recorded with its cause while the sweep goes on, resuming, shards,
// bad input, and the charts' files with their labels; the scene cases (scene:NAME) likewise.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_helper.h"
#include "scene/scene.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

// 2 solvers x 2 spacings x 2 factors on the dam break; WCSPH at a time-step factor of 10 leaves the
// tank within its first frame at 0.025 m (the sound-speed condition broken tenfold).
const std::vector<std::string> kTiny = {"sweep", "--cases", "dam-break", "--solvers", "dfsph,wcsph", "--spacings", "0.04,0.025",
                                        "--factors", "1,10", "--quiet"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);)
        if (!l.empty()) out.push_back(l);
    return out;
}

// scene-settings.py --json's "scenes", keyed "scene@spacing" (e.g. "dam-break@0.0125").
std::map<std::string, nlohmann::json> choices_by_scene(const nlohmann::json& choices) {
    std::map<std::string, nlohmann::json> by;
    for (const auto& s : choices["scenes"]) {
        char key[120];
        std::snprintf(key, sizeof key, "%s@%g", s["scene"].get<std::string>().c_str(), s["spacing"].get<double>());
        by[key] = s;
    }
    return by;
}

// The rule's verdict on one row of a scene's choice: "eligible", why not, or "absent".
std::string verdict(const nlohmann::json& scene, const std::string& key) {
    for (const auto& row : scene["rows"])
        if (row["key"] == key) return row["why_not"].is_null() ? std::string("eligible") : row["why_not"].get<std::string>();
    return "absent";
}

}  // namespace

TEST_CASE("sweep: a tiny sweep writes a row a run with every field, records the unstable one with its cause, and resumes",
          "[sweep]") {
    TempDir dir;
    const fs::path out = dir.path() / "sw";
    RunOptions slow;
    slow.timeout = std::chrono::seconds(400);
    const Result r = run_ranryu(dir.path(), with(kTiny, {"--out", out.string()}), slow);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("8 run ("));
    CHECK_THAT(r.out, Contains("0 already done"));

    const auto j = nlohmann::json::parse(read_file(out / "sweep.json"));
    REQUIRE(j["rows"].size() == 8);
    std::set<std::string> keys;
    for (const auto& row : j["rows"]) {
        INFO(row.dump());
        keys.insert(row["key"].get<std::string>());
        for (const char* f : {"case", "solver", "spacing", "factor", "cfl", "status", "device", "date"}) CHECK(row.contains(f));
        CHECK(row["cfl"].get<double>() == Approx(0.4 * row["factor"].get<double>()).epsilon(1e-5));
        // DFSPH's own Courant number, which the dam break sets (docs/DFSPH.md (D8)), scales too; WCSPH's rows
        // do not carry it.
        if (row["solver"] == "dfsph") CHECK(row["dfsph_cfl"].get<double>() == Approx(0.5 * row["factor"].get<double>()).epsilon(1e-5));
        else CHECK_FALSE(row.contains("dfsph_cfl"));
        if (row["status"] == "unstable" && row["failure_cause"] == "energy gain") {
            // Ran to the end making energy: the sweep's own criterion (app/sweep.cpp), not the guard's.
            CHECK(row["key"].get<std::string>().ends_with("/10"));
            CHECK(row["energy_drift"].get<double>() > 0.01);
            CHECK(row["failure_frame"].is_null());
            CHECK_THAT(row["failure_message"].get<std::string>(), Contains("energy grew"));
        } else if (row["key"] == "dam-break/wcsph/0.025/10" || (row["key"] == "dam-break/wcsph/0.04/10" && row["status"] == "unstable")) {
            // WCSPH at ten times its time step: unstable at 0.025 m; at 0.04 m it survives or not by
            // the last bits of the flow (the kernel's rounding has tipped it either way).
            CHECK(row["status"] == "unstable");
            CHECK(row["failure_frame"].get<int>() >= 0);
            CHECK(row["failure_time"].get<double>() > 0.0);
            // The guard's cause: the density bound, or (had the projection let one through) a particle out.
            CHECK_THAT(row["failure_cause"].get<std::string>(), Contains("beyond its bound") || Contains("left the domain"));
            CHECK_THAT(row["failure_message"].get<std::string>(), Contains("unstable at frame"));
            CHECK_FALSE(row.contains("error"));
        } else {
            CHECK(row["status"] == "stable");
            // The front's error in Z is a few spacings at most (a/dx = 5 and 8); the rest are
            // physical: compression of at most the guard's bound, energy that the flow loses.
            CHECK(row["error"].get<double>() >= 0.0);
            CHECK(row["error"].get<double>() < 2.0);
            CHECK(row["error_max"].get<double>() >= row["error"].get<double>());
            CHECK(row["particles"].get<int>() > 0);
            CHECK(row["steps"].get<int>() > 0);
            CHECK(row["simulated_seconds"].get<double>() > 0.3);
            CHECK(row["wall_seconds"].get<double>() > 0.0);
            CHECK(row["gpu_ms_per_simulated_second"].get<double>() >= 0.0);
            CHECK(row["max_density_deviation"].get<double>() >= 0.0);
            CHECK(row["max_density_deviation"].get<double>() < 0.5);
            CHECK(row["mean_density_deviation"].get<double>() >= 0.0);
            CHECK(row["mean_density_deviation"].get<double>() <= row["max_density_deviation"].get<double>());
            CHECK(row["energy_drift"].get<double>() < 0.0);   // the dam break only loses energy
            // These coarse dam breaks stay well inside the guard's bounds (max deviation < 0.5 above):
            // no frame past one, so no spike let pass.
            CHECK(row["guard_spikes"].get<int>() == 0);
            CHECK(row["energy_drift"].get<double>() > -1.0);
        }
    }
    CHECK(keys.size() == 8);
    // WCSPH takes more steps than DFSPH on the same settings.
    auto steps = [&](const std::string& key) {
        for (const auto& row : j["rows"])
            if (row["key"] == key) return row["steps"].get<int>();
        return -1;
    };
    CHECK(steps("dam-break/wcsph/0.025/1") > 3 * steps("dam-break/dfsph/0.025/1"));

    const std::vector<std::string> csv = lines(read_file(out / "sweep.csv"));
    REQUIRE(csv.size() == 9);
    CHECK_THAT(csv[0], Contains("key,case,solver,spacing,factor"));
    CHECK_THAT(csv[0], Contains("gpu_ms_per_simulated_second"));

    // A second invocation finds every row done and runs none; the files keep their rows.
    const Result again = run_ranryu(dir.path(), with(kTiny, {"--out", out.string()}), slow);
    INFO(again.out << again.err);
    REQUIRE(again.exit_code == 0);
    CHECK_THAT(again.out, Contains("0 run (0 unstable), 8 already done"));
    // Every factor-1 run is sound.
    for (const auto& row : j["rows"])
        if (row["factor"].get<double>() == 1.0) CHECK(row["status"] == "stable");
    CHECK(nlohmann::json::parse(read_file(out / "sweep.json"))["rows"].size() == 8);

    SECTION("the charts: PNG and SVG, with the axes' and legends' labels as text") {
        // matplotlib is a runtime option of the chart script (scripts/install-deps.sh installs it).
        if (run({"/usr/bin/python3", "-c", "import matplotlib"}).exit_code != 0) {
            if (env_is("RANRYU_REQUIRE_MATPLOTLIB", "1")) FAIL("python3-matplotlib is missing, and RANRYU_REQUIRE_MATPLOTLIB=1 requires the charts");
            WARN("skipped: python3-matplotlib is missing (RANRYU_REQUIRE_MATPLOTLIB=1 makes this a failure)");
            return;
        }
        const fs::path charts = dir.path() / "charts";
        const Result c = run({"/usr/bin/python3", (source_dir() / "scripts" / "sweep-charts.py").string(), (out / "sweep.json").string(),
                              "--out", charts.string()});
        INFO(c.out << c.err);
        REQUIRE(c.exit_code == 0);
        for (const char* f : {"accuracy-vs-cost.png", "accuracy-vs-cost.svg", "stability-map.png", "stability-map.svg"}) {
            INFO(f);
            REQUIRE(fs::exists(charts / f));
            CHECK(fs::file_size(charts / f) > 5000);
        }
        CHECK(read_file(charts / "accuracy-vs-cost.png").substr(1, 3) == "PNG");
        const std::string acc = read_file(charts / "accuracy-vs-cost.svg"), map = read_file(charts / "stability-map.svg");
        for (const char* label : {"cost: GPU ms per simulated second", "surge front rms error in Z", "dfsph Pareto front",
                                  "wcsph Pareto front", "dam-break: accuracy against cost"})
            CHECK_THAT(acc, Contains(label));
        for (const char* label : {"time-step factor", "particle spacing (m)", "stability: dam-break, dfsph", "stability: dam-break, wcsph",
                                  "stable"})
            CHECK_THAT(map, Contains(label));
        // The unstable row's cell names its cause (the density bound; "escaped" had a particle got out).
        CHECK_THAT(map, Contains("density") || Contains("escaped"));
    }
}

TEST_CASE("sweep: --shard I/N partitions the rows exactly, and --list runs nothing", "[sweep]") {
    TempDir dir;
    const std::vector<std::string> all = lines(run_ranryu(dir.path(), {"sweep", "--quick", "--list"}).out);
    REQUIRE(all.size() == 16);
    std::multiset<std::string> union_;
    for (int i = 1; i <= 3; ++i) {
        const Result r = run_ranryu(dir.path(), {"sweep", "--quick", "--list", "--shard", std::to_string(i) + "/3"});
        REQUIRE(r.exit_code == 0);
        for (const std::string& l : lines(r.out)) {
            const int k = std::stoi(l.substr(0, l.find(' ')));
            CHECK(k % 3 == i - 1);
            union_.insert(l);
        }
    }
    CHECK(union_ == std::multiset<std::string>(all.begin(), all.end()));
    CHECK(fs::is_empty(dir.path()));
}

TEST_CASE("sweep: bad input is refused with one line naming it, and a foreign sweep.json is left alone", "[sweep]") {
    TempDir dir;
    for (const auto& args : std::vector<std::vector<std::string>>{{"sweep", "--quick"},
                                                                 {"sweep", "--quick", "--list", "--shard", "3/2"},
                                                                 {"sweep", "--quick", "--list", "--shard", "x"},
                                                                 {"sweep", "--quick", "--list", "--factors", "0"},
                                                                 {"sweep", "--quick", "--list", "--factors", "1,,2"},
                                                                 {"sweep", "--quick", "--list", "--cases", "tsunami"},
                                                                 {"sweep", "--quick", "--list", "--solvers", "sph"}}) {
        const Result r = run_ranryu(dir.path(), args);
        INFO(r.err);
        CHECK(r.exit_code == 2);
        CHECK(lines(r.err).size() == 1);
    }
    const fs::path out = dir.path() / "other";
    fs::create_directories(out);
    write_file(out / "sweep.json", "{\"not\": \"a sweep\"}");
    const Result r = run_ranryu(dir.path(), {"sweep", "--quick", "--out", out.string()});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains((out / "sweep.json").string()));
    CHECK(read_file(out / "sweep.json") == "{\"not\": \"a sweep\"}");
    CHECK_FALSE(fs::exists(out / "sweep.csv"));
}

TEST_CASE("sweep: a PBF row's factor divides its fixed substeps and keeps its iterations", "[sweep][pbf]") {
    TempDir dir;
    const fs::path out = dir.path() / "sw";
    RunOptions slow;
    slow.timeout = std::chrono::seconds(400);
    const Result r = run_ranryu(dir.path(), {"sweep", "--cases", "dam-break", "--solvers", "pbf", "--spacings", "0.04", "--factors",
                                             "0.5,1,2", "--quiet", "--out", out.string()}, slow);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(read_file(out / "sweep.json"));
    REQUIRE(j["rows"].size() == 3);
    std::map<double, nlohmann::json> by_factor;
    for (const auto& row : j["rows"]) by_factor[row["factor"].get<double>()] = row;
    // docs/SWEEP.md "PBF and the factor": the dam break's 4 substeps at its own 0.0125 m are
    // ceil(4 · 0.0125 / 0.04) = 2 at 0.04 m (docs/PBF.md "Resolution"), and a row runs round(2 / f).
    const std::map<double, int> substeps = {{0.5, 4}, {1.0, 2}, {2.0, 1}};
    for (const auto& [factor, want] : substeps) {
        const nlohmann::json& row = by_factor.at(factor);
        INFO(row.dump());
        CHECK(row["solver"] == "pbf");
        CHECK(row["pbf_substeps"] == want);
        CHECK(row["pbf_iterations"] == 4);
        CHECK(row["status"] == "stable");
    }
    // The work follows: the steps a run took scale with the substeps (the same simulated time).
    const auto steps = [&](double f) { return by_factor.at(f)["steps"].get<double>(); };
    CHECK(steps(0.5) == Approx(2.0 * steps(1.0)).epsilon(0.02));
    CHECK(steps(1.0) == Approx(2.0 * steps(2.0)).epsilon(0.02));
}

TEST_CASE("sweep: a scene case runs the bundled scene for --seconds with its compression, the guard's verdict, the energy "
          "criterion that fits it, and resumes only at the same --seconds",
          "[sweep][scenes]") {
    TempDir dir;
    const fs::path out = dir.path() / "sw";
    RunOptions slow;
    slow.timeout = std::chrono::seconds(400);
    // The dam break at a coarse spacing with WCSPH at factors 1 and 10 (10 leaves the tank within
    // its first frames, as in the validation case), then the turbulent jet with PBF into the same folder.
    const std::vector<std::string> dam = {"sweep", "--cases", "scene:dam-break", "--solvers", "wcsph", "--spacings", "0.025",
                                          "--factors", "1,10", "--seconds", "1", "--quiet", "--out", out.string()};
    const Result r = run_ranryu(dir.path(), dam, slow);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("2 run (1 unstable)"));
    const Result jet = run_ranryu(dir.path(), {"sweep", "--cases", "scene:turbulent-jet", "--solvers", "pbf", "--spacings", "0.04",
                                               "--factors", "1", "--seconds", "1", "--quiet", "--out", out.string()}, slow);
    INFO(jet.out << jet.err);
    REQUIRE(jet.exit_code == 0);
    CHECK_THAT(jet.out, Contains("1 run (0 unstable), 0 already done"));

    const auto j = nlohmann::json::parse(read_file(out / "sweep.json"));
    REQUIRE(j["rows"].size() == 3);
    std::map<std::string, nlohmann::json> rows;
    for (const auto& row : j["rows"]) rows[row["key"].get<std::string>()] = row;
    REQUIRE(rows.count("scene:dam-break/wcsph/0.025/1"));
    REQUIRE(rows.count("scene:dam-break/wcsph/0.025/10"));
    REQUIRE(rows.count("scene:turbulent-jet/pbf/0.04/1"));
    for (const auto& [key, row] : rows) {
        INFO(row.dump());
        CHECK(row["seconds"].get<double>() == 1.0);
        for (const char* f : {"case", "solver", "spacing", "factor", "cfl", "status", "device", "date", "energy_check", "particles"})
            CHECK(row.contains(f));
    }
    const nlohmann::json& bad = rows["scene:dam-break/wcsph/0.025/10"];
    CHECK(bad["status"] == "unstable");
    CHECK(bad["failure_frame"].get<int>() >= 0);
    CHECK(bad["failure_time"].get<double>() < 1.0);
    CHECK_THAT(bad["failure_message"].get<std::string>(), Contains("unstable at frame"));
    CHECK_FALSE(bad.contains("mean_density_deviation_peak"));
    for (const char* key : {"scene:dam-break/wcsph/0.025/1", "scene:turbulent-jet/pbf/0.04/1"}) {
        const nlohmann::json& row = rows[key];
        INFO(row.dump());
        CHECK(row["status"] == "stable");
        CHECK(row["simulated_seconds"].get<double>() == Approx(1.0).epsilon(1e-3));
        CHECK(row["steps"].get<int>() > 0);
        CHECK(row["gpu_ms_per_simulated_second"].get<double>() >= 0.0);
        // The worst frame's mean compression: at least the average's and the end's, at most the worst particle's.
        const double peak = row["mean_density_deviation_peak"].get<double>();
        CHECK(peak >= row["mean_density_deviation_average"].get<double>());
        CHECK(peak >= row["mean_density_deviation"].get<double>());
        CHECK(peak <= row["max_density_deviation"].get<double>());
        CHECK(peak < 0.05);
        CHECK(row["mean_density_deviation_peak_time"].get<double>() > 0.0);
        CHECK(row["error"].get<double>() == peak);
        CHECK(row["error_max"].get<double>() == row["max_density_deviation"].get<double>());
        CHECK_THAT(row["error_name"].get<std::string>(), Contains("mean compression"));
    }
    // The energy criterion: a closed tank under gravity is checked for a gain; the jet, whose
    // turbulence force does work on the fluid, is not.
    CHECK_THAT(rows["scene:dam-break/wcsph/0.025/1"]["energy_check"].get<std::string>(), Contains("gain above 1 %"));
    CHECK(rows["scene:dam-break/wcsph/0.025/1"]["energy_drift"].get<double>() < 0.0);
    CHECK_THAT(rows["scene:turbulent-jet/pbf/0.04/1"]["energy_check"].get<std::string>(), Contains("turbulence force"));
    // The jet's 4 substeps at its own 0.025 m are ceil(4 · 0.025 / 0.04) = 3 at 0.04 m (docs/PBF.md "Resolution").
    CHECK(rows["scene:turbulent-jet/pbf/0.04/1"]["pbf_substeps"] == 3);
    const std::vector<std::string> csv = lines(read_file(out / "sweep.csv"));
    REQUIRE(csv.size() == 4);
    CHECK_THAT(csv[0], Contains("seconds,mean_density_deviation_peak"));

    // Resumed at the same --seconds: nothing runs. At another: refused before any run, naming the
    // folder's file, the row and both durations; the rows stay as they were.
    const Result again = run_ranryu(dir.path(), dam, slow);
    INFO(again.out << again.err);
    CHECK(again.exit_code == 0);
    CHECK_THAT(again.out, Contains("0 run (0 unstable), 2 already done"));
    std::vector<std::string> longer = dam;
    REQUIRE(longer[9] == "--seconds");
    longer[10] = "2";
    const std::string before = read_file(out / "sweep.json");
    const Result refused = run_ranryu(dir.path(), longer, slow);
    INFO(refused.out << refused.err);
    CHECK(refused.exit_code == 2);
    CHECK(lines(refused.err).size() == 1);
    CHECK_THAT(refused.err, Contains((out / "sweep.json").string()));
    CHECK_THAT(refused.err, Contains("scene:dam-break/wcsph/0.025/1 ran 1 simulated seconds, and --seconds asks for 2"));
    CHECK(read_file(out / "sweep.json") == before);
}

TEST_CASE("sweep: the scene cases are the bundled SPH scenes at their own spacings, and bad scene cases are refused",
          "[sweep][scenes]") {
    TempDir dir;
    const Result r = run_ranryu(dir.path(), {"sweep", "--cases", "scenes", "--solvers", "dfsph", "--factors", "1", "--list"});
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    std::set<std::string> listed;
    for (const std::string& l : lines(r.out)) listed.insert(l.substr(l.find(' ') + 1));
    std::set<std::string> want;
    for (const ranryu::scene::BundledScene& b : ranryu::scene::bundled()) {
        const ranryu::scene::Scene s = ranryu::scene::load(b.name);
        if (s.model != ranryu::scene::Model::sph) continue;
        char key[200];
        std::snprintf(key, sizeof key, "scene:%s/dfsph/%.6g/1", b.name.c_str(), s.spacing);
        want.insert(key);
    }
    CHECK(want.size() >= 4);
    CHECK(listed == want);
    CHECK_FALSE(r.out.find("falling-block") != std::string::npos);   // no SPH, no solver to sweep
    // --shard partitions scene rows like any others.
    std::multiset<std::string> union_;
    for (int i = 1; i <= 2; ++i)
        for (const std::string& l : lines(run_ranryu(dir.path(), {"sweep", "--cases", "scenes", "--solvers", "dfsph", "--factors",
                                                                  "1", "--list", "--shard", std::to_string(i) + "/2"}).out))
            union_.insert(l);
    const std::vector<std::string> all_rows = lines(r.out);
    CHECK(union_ == std::multiset<std::string>(all_rows.begin(), all_rows.end()));

    const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
        {{"--cases", "scene:falling-block"}, "ballistic model"},
        {{"--cases", "scene:tsunami"}, "no bundled SPH scene of that name"},
        {{"--cases", "scenes,scene:drop"}, "named twice"},
        {{"--cases", "dam-break", "--seconds", "2"}, "--seconds: only the scene cases"},
        {{"--cases", "scene:drop", "--seconds", "0"}, "--seconds 0"},
        {{"--cases", "scene:drop", "--seconds", "x"}, "--seconds x"},
    };
    for (const auto& [args, says] : bad) {
        std::vector<std::string> all = {"sweep", "--list"};
        all.insert(all.end(), args.begin(), args.end());
        const Result b = run_ranryu(dir.path(), all);
        INFO(b.err);
        CHECK(b.exit_code == 2);
        CHECK(lines(b.err).size() == 1);
        CHECK_THAT(b.err, Contains(says));
    }
    CHECK(fs::is_empty(dir.path()));
}

TEST_CASE("scene-settings.py: from a sweep's scene rows, each scene's cheapest eligible setting and the keys to put in its file",
          "[sweep][scenes][script]") {
    // tests/data/sweeps/scene-settings.json: rows made up to meet each clause of the rule once
    // (docs/SWEEP.md "Choosing a scene's settings").
    TempDir dir;
    const fs::path script = source_dir() / "scripts" / "scene-settings.py";
    const fs::path rows = kData / "sweeps" / "scene-settings.json";
    const Result r = run({"/usr/bin/python3", script.string(), rows.string(), "--json", (dir / "choices.json").string()});
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    const auto j = nlohmann::json::parse(read_file(dir / "choices.json"));
    CHECK(j["max_compression"] == 0.01);
    CHECK(j["seconds"] == 10.0);
    const std::map<std::string, nlohmann::json> by = choices_by_scene(j);
    // The validation case's row is not a scene's: four scenes, the dam break at two spacings.
    REQUIRE(by.size() == 5);

    // The dam break: the cheaper rows fail one clause each, and wcsph x2 is chosen by its GPU time.
    const nlohmann::json& dam = by.at("dam-break@0.0125");
    INFO(dam.dump(1));
    CHECK(dam["cost_measure"] == "gpu_ms_per_simulated_second");
    CHECK(dam["chosen"] == "scene:dam-break/wcsph/0.0125/2");
    CHECK(dam["own_spacing"] == true);
    CHECK(dam["sph"]["solver"] == "wcsph");
    CHECK(dam["sph"]["cfl"] == 0.8);   // the row's 0.80000001192... as the file should say it
    CHECK(dam["sph"]["force_factor"] == 0.5);
    CHECK(dam["sph"]["max_time_step"] == 0.01);
    const std::string why = dam["sph"]["why"].get<std::string>();
    for (const char* says : {"NVIDIA H100", "2026-12-01", "10 s stable", "at most 1 %", "2000 GPU ms a simulated second",
                             "against 2500 for dfsph x2", "docs/SWEEP.md"})
        CHECK_THAT(why, Contains(says));
    CHECK_THAT(verdict(dam, "scene:dam-break/pbf/0.0125/1"), Contains("mean compression reached 2 %"));
    CHECK_THAT(verdict(dam, "scene:dam-break/pbf/0.0125/0.5"), Contains("a smaller factor, x0.25, is not sound"));
    CHECK_THAT(verdict(dam, "scene:dam-break/pbf/0.0125/0.25"), Contains("unstable: energy gain"));
    CHECK_THAT(verdict(dam, "scene:dam-break/wcsph/0.0125/3"), Contains("sph.cfl = 1.2 is outside the scene key's bounds [0.01, 1]"));
    CHECK_THAT(verdict(dam, "scene:dam-break/dfsph/0.0125/2.5"), Contains("unstable: simulation unstable at frame 7"));
    CHECK(verdict(dam, "scene:dam-break/dfsph/0.0125/1") == "eligible");
    // DFSPH's own Courant number (sph.dfsph_cfl, which the dam break sets) is held to its key's bounds too.
    CHECK_THAT(verdict(dam, "scene:dam-break/dfsph/0.0125/2.2"), Contains("sph.dfsph_cfl = 1.1 is outside the scene key's bounds [0, 1]"));
    // ... in place of sph.cfl, which the row's DFSPH step did not read (made up out of bounds here).
    CHECK(verdict(dam, "scene:dam-break/dfsph/0.0125/1.2") == "eligible");
    CHECK_THAT(r.out, Contains("merge into media/scenes/dam-break.json's \"sph\": {\"solver\": \"wcsph\", \"cfl\": 0.8,"));

    // The same scene at a spacing its file does not have: chosen, and said to need that spacing.
    const nlohmann::json& fine = by.at("dam-break@0.00625");
    CHECK(fine["chosen"] == "scene:dam-break/dfsph/0.00625/1");
    CHECK(fine["own_spacing"] == false);
    CHECK(fine["sph"] == nlohmann::json{{"solver", "dfsph"}, {"why", fine["sph"]["why"]}});   // factor 1: the step keys stay the scene's
    CHECK_THAT(r.out, Contains("only if its spacing becomes 0.00625 (the file's is 0.0125"));

    // The jet gains energy from its turbulence force, which is no instability there: PBF is chosen,
    // with its substeps and iterations.
    const nlohmann::json& jet = by.at("turbulent-jet@0.025");
    CHECK(jet["chosen"] == "scene:turbulent-jet/pbf/0.025/1");
    CHECK(jet["sph"]["pbf"] == nlohmann::json{{"substeps", 4}, {"iterations", 4}});
    CHECK_FALSE(jet["sph"].contains("cfl"));

    // The drop ran 2 of the 10 seconds asked: no choice, and the output says to keep the scene's.
    const nlohmann::json& drop = by.at("drop@0.015");
    CHECK(drop["chosen"].is_null());
    CHECK(drop["sph"].is_null());
    CHECK_THAT(verdict(drop, "scene:drop/dfsph/0.015/1"), Contains("ran 2 s of the 10 s asked"));
    CHECK_THAT(r.out, Contains("no setting is eligible"));
    // ... unless the rule is asked for 2 seconds.
    const Result two = run({"/usr/bin/python3", script.string(), rows.string(), "--seconds", "2", "--json", (dir / "two.json").string()});
    REQUIRE(two.exit_code == 0);
    // The choices file's chosen key for a scene and spacing ("absent" where the file has no such scene),
    // read from a named json: a loop over a temporary's ["scenes"] would walk freed memory.
    auto chosen_in = [&](const fs::path& file, const std::string& scene, double spacing) {
        const auto choices = nlohmann::json::parse(read_file(file));
        for (const auto& s : choices["scenes"])
            if (s["scene"] == scene && s["spacing"] == spacing)
                return s["chosen"].is_null() ? std::string("none") : s["chosen"].get<std::string>();
        return std::string("absent");
    };
    CHECK(chosen_in(dir / "two.json", "drop", 0.015) == "scene:drop/wcsph/0.015/1");

    // A row timed on llvmpipe makes the tank at rest's costs steps: DFSPH's fewer steps win over
    // WCSPH's smaller (software) time.
    const nlohmann::json& tank = by.at("hydrostatic@0.0125");
    CHECK(tank["cost_measure"] == "steps");
    CHECK(tank["chosen"] == "scene:hydrostatic/dfsph/0.0125/1");
    CHECK_THAT(tank["sph"]["why"].get<std::string>(), Contains("250 steps a simulated second against 5000 for wcsph x1"));

    // The largest density is held to --max-density (1.3 rho0 by default): at 1.055 rho0 WCSPH x2 (its
    // densest frame 1.06 rho0 in the made-up row) is out, and DFSPH x2 (1.05) is chosen.
    CHECK(j["max_density"] == 1.3);
    const Result margin = run({"/usr/bin/python3", script.string(), rows.string(), "--max-density", "1.055", "--json",
                               (dir / "margin.json").string()});
    REQUIRE(margin.exit_code == 0);
    CHECK(chosen_in(dir / "margin.json", "dam-break", 0.0125) == "scene:dam-break/dfsph/0.0125/2");

    // A stricter bound on the compression moves the dam break's choice to DFSPH.
    const Result strict = run({"/usr/bin/python3", script.string(), rows.string(), "--max-compression", "0.001", "--json",
                               (dir / "strict.json").string()});
    REQUIRE(strict.exit_code == 0);
    CHECK(chosen_in(dir / "strict.json", "dam-break", 0.0125) == "scene:dam-break/dfsph/0.0125/2");

    // Bad input: one line on stderr naming it, exit code 2.
    write_file(dir / "foreign.json", "{\"not\": \"a sweep\"}");
    write_file(dir / "no-scenes.json", "{\"rows\": []}");
    const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
        {{(dir / "foreign.json").string()}, (dir / "foreign.json").string() + ": not a sweep's rows"},
        {{(dir / "missing").string()}, "missing"},
        {{(dir / "no-scenes.json").string()}, "no scene case's rows"},
        {{rows.string(), "--max-compression", "2"}, "--max-compression 2"},
        {{rows.string(), "--seconds", "x"}, "--seconds"},
        {{rows.string(), "--max-density", "0.9"}, "--max-density 0.9"},
    };
    for (const auto& [args, says] : bad) {
        std::vector<std::string> argv = {"/usr/bin/python3", script.string()};
        argv.insert(argv.end(), args.begin(), args.end());
        const Result b = run(argv);
        INFO(b.err);
        CHECK(b.exit_code == 2);
        CHECK(lines(b.err).size() == 1);
        CHECK_THAT(b.err, Contains(says));
    }
}

TEST_CASE("scene-settings.py --at-scale: a setting is chosen only where it is sound at the scene's other sizes too",
          "[sweep][scenes][script]") {
    // tests/data/sweeps/scene-settings-at-scale.json: the dam break of scene-settings.json at two
    // larger spacings, rows made up so that each clause of --at-scale decides one setting.
    TempDir dir;
    const fs::path script = source_dir() / "scripts" / "scene-settings.py";
    const fs::path rows = kData / "sweeps" / "scene-settings.json";
    const fs::path scale = kData / "sweeps" / "scene-settings-at-scale.json";
    const Result r = run({"/usr/bin/python3", script.string(), rows.string(), "--at-scale", scale.string(), "--json",
                          (dir / "choices.json").string()});
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    const auto j = nlohmann::json::parse(read_file(dir / "choices.json"));
    const std::map<std::string, nlohmann::json> by = choices_by_scene(j);
    REQUIRE(by.size() == 5);   // the larger sizes' rows are checks, not scenes of their own
    const nlohmann::json& dam = by.at("dam-break@0.0125");
    INFO(dam.dump(1));
    CHECK(dam["at_scale"] == nlohmann::json::array({0.003, 0.002}));
    // WCSPH x2, the choice without --at-scale, is unstable at 0.003 m: DFSPH x2, sound at both sizes, is chosen.
    CHECK_THAT(verdict(dam, "scene:dam-break/wcsph/0.0125/2"),
               Contains("at 0.003 m (246078 particles): unstable: simulation unstable at frame 40"));
    CHECK(dam["chosen"] == "scene:dam-break/dfsph/0.0125/2");
    CHECK_THAT(dam["sph"]["why"].get<std::string>(),
               Contains("held as well at 0.003 m (246078 particles) and 0.002 m (1000000 particles)"));
    // A setting missing at one size is not eligible; one that compresses past the bound there, or
    // comes within 0.2 rho0 of the guard's bound (--max-density, 1.3 by default), neither.
    CHECK(verdict(dam, "scene:dam-break/wcsph/0.0125/1") == "not run at 0.003 m (the --at-scale rows' spacing for this scene)");
    CHECK_THAT(verdict(dam, "scene:dam-break/dfsph/0.0125/1"), Contains("at 0.002 m (1000000 particles): mean compression reached 2 %"));
    CHECK_THAT(verdict(dam, "scene:dam-break/dfsph/0.0125/1.2"),
               Contains("at 0.002 m (1000000 particles): largest density 1.35 rho0 > 1.3 rho0"));
    // The clauses before it still decide first.
    CHECK_THAT(verdict(dam, "scene:dam-break/dfsph/0.0125/2.2"), Contains("outside the scene key's bounds"));
    CHECK_THAT(r.out, Contains("each setting checked at 0.003, 0.002 m as well"));
    // The same scene's other spacing is held to the larger sizes too: DFSPH x1 compresses at 1M, so no choice.
    CHECK(by.at("dam-break@0.00625")["chosen"].is_null());
    // The scale rows' own-spacing row (made up unstable) is not a larger size and does not count, and
    // the 1M row of DFSPH x2, its factor stored as 2.0000000001, is that factor's.
    CHECK(verdict(dam, "scene:dam-break/dfsph/0.0125/2") == "eligible");
    // Scenes without rows at other sizes choose as before, and the printout says they were not checked.
    CHECK(by.at("turbulent-jet@0.025")["chosen"] == "scene:turbulent-jet/pbf/0.025/1");
    CHECK(by.at("turbulent-jet@0.025")["at_scale"].empty());
    CHECK_THAT(r.out, Contains("turbulent-jet at spacing 0.025 (cost: gpu_ms_per_simulated_second; not checked at other sizes"));

    // Bad input there: one line naming it, exit code 2.
    for (const std::vector<std::string>& args : {std::vector<std::string>{"--at-scale", (dir / "missing.json").string()},
                                                 std::vector<std::string>{"--at-scale"}}) {
        std::vector<std::string> argv = {"/usr/bin/python3", script.string(), rows.string()};
        argv.insert(argv.end(), args.begin(), args.end());
        const Result b = run(argv);
        INFO(b.err);
        CHECK(b.exit_code == 2);
        CHECK(lines(b.err).size() == 1);
        CHECK_THAT(b.err, Contains("--at-scale") || Contains("missing.json"));
    }
}

TEST_CASE("scripts/gpu/scene-settings.sh smoke: the GPU host's scene sweep and its choice run end to end on llvmpipe",
          "[sweep][scenes][script]") {
    // The script the lead runs on the H100, at 0.1 s a row and spacing 0.04, one factor a solver:
    // every scene and solver swept into one folder, the rule applied, its six files written.
    TempDir dir;
    RunOptions opt;
    opt.timeout = std::chrono::seconds(300);
    opt.set_env = {{"OUT", dir.str("out")}, {"RANRYU_BIN", kBin}};
    const Result r = run({"/bin/bash", (source_dir() / "scripts" / "gpu" / "scene-settings.sh").string(), "smoke"}, opt);
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    for (const char* f : {"sweep.json", "sweep.csv", "sweep.log", "scene-settings.txt", "scene-settings.json", "summary.txt"})
        CHECK(fs::exists(dir / "out" / f));
    const auto rows = nlohmann::json::parse(read_file(dir / "out" / "sweep.json"))["rows"];
    std::size_t sph_scenes = 0;
    for (const ranryu::scene::BundledScene& b : ranryu::scene::bundled())
        if (ranryu::scene::load(b.name).model == ranryu::scene::Model::sph) ++sph_scenes;
    CHECK(rows.size() == 3 * sph_scenes);   // pbf, dfsph and wcsph at factor 1, each scene
    const auto choices = nlohmann::json::parse(read_file(dir / "out" / "scene-settings.json"));
    CHECK(choices["seconds"].get<double>() == Approx(0.1));
    CHECK(choices["scenes"].size() == sph_scenes);
    CHECK_THAT(r.out, Contains("scene-settings.py: rc 0"));
    CHECK_THAT(r.out, !Contains("not run or cut short"));

    // No budget: no sweep runs, and the summary says what was not run.
    opt.set_env = {{"OUT", dir.str("none")}, {"RANRYU_BIN", kBin}, {"BUDGET_SECONDS", "0"}};
    const Result none = run({"/bin/bash", (source_dir() / "scripts" / "gpu" / "scene-settings.sh").string(), "smoke"}, opt);
    INFO(none.describe());
    CHECK_THAT(none.out, Contains("not run or cut short"));
    CHECK_THAT(none.out, Contains("scene:dam-break pbf"));
    CHECK_FALSE(fs::exists(dir / "none" / "sweep.json"));
}

TEST_CASE("sweep: the impact cases' rows carry the sensors' pressure error after the impact", "[sweep]") {
    // Each case through the sweep at a coarse spacing (impact-pressure at 0.05 m, H/dx = 6; obstacle-impact
    // at 0.1 m): the row is the case's own run (its sensors named, the error their mean rms and the error_max
    // their largest; docs/VALIDATION.md "Impact pressure"), not another case's.
    TempDir dir;
    RunOptions slow;
    slow.timeout = std::chrono::seconds(300);
    const std::pair<const char*, const char*> runs[] = {{"impact-pressure", "0.05"}, {"obstacle-impact", "0.1"}};
    for (const auto& [name, dx] : runs) {
        INFO(name);
        const fs::path out = dir.path() / name;
        const Result r = run_ranryu(dir.path(), {"sweep", "--cases", name, "--solvers", "dfsph", "--spacings", dx, "--factors", "1", "--out",
                                                 out.string(), "--quiet"},
                                    slow);
        INFO(r.out << r.err);
        REQUIRE(r.exit_code == 0);
        const auto j = nlohmann::json::parse(read_file(out / "sweep.json"));
        REQUIRE(j["rows"].size() == 1);
        const auto& row = j["rows"][0];
        INFO(row.dump().substr(0, 600));
        CHECK(row["case"] == name);
        CHECK(row["status"] == "stable");
        const std::vector<std::string> sensors = std::string(name) == "impact-pressure" ? std::vector<std::string>{"P1", "P3", "P4"}
                                                                                        : std::vector<std::string>{"P1", "P3"};
        REQUIRE(row["sensors"].size() == sensors.size());
        double sum = 0.0, most = 0.0;
        for (const std::string& s : sensors) {
            REQUIRE(row["sensors"].contains(s));
            const double e = row["sensors"][s]["rms_error"].get<double>();
            CHECK(e > 0.0);
            sum += e, most = std::max(most, e);
        }
        CHECK(row["error"].get<double>() == Approx(sum / double(sensors.size())).epsilon(1e-12));
        CHECK(row["error_max"].get<double>() == Approx(most).epsilon(1e-12));
        CHECK_THAT(row["error_name"].get<std::string>(),
                   Contains(std::string(name) == "impact-pressure" ? "Lobovsky et al. 2014" : "Kleefsman et al. 2005"));
    }
}
