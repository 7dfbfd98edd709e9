// ranryu profile: the timing table on stdout, and the same report as --json and --csv files.
// llvmpipe's timer queries read about 0, so timings are only checked to be numbers >= 0.
#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <map>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "run_helper.h"

using namespace ranryu::test;
using Catch::Matchers::Contains;

namespace {

// The passes every frame of every scene runs today (renderer and particle passes).
const std::vector<std::string> kFramePasses = {"ballistic.integrate", "clear", "draw-floor", "draw-tank", "draw-particles"};

struct Row {
    std::string name;
    double calls = -1, min = -1, median = -1, max = -1, per_call = -1, share = -1;
};

struct Table {
    std::vector<std::string> header;   // the column titles, as printed
    std::vector<Row> rows;             // every row after the header, "frame (GPU span)" included
    std::size_t particles = 0;
    std::string scene;
};

double number(const std::string& text) {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument("not a number: " + text);
    return v;
}

// Parses the table `ranryu profile` prints: a header line starting with "pass", then one row per
// pass: NAME (may contain spaces) and five numbers, the last a percentage, up to a blank line.
Table parse_table(const std::string& out) {
    Table t;
    const auto lines = Result::split_lines(out);
    std::size_t i = 0;
    static const std::regex scene_line(R"(^scene (\S+): (\d+) particles, .*)");
    for (; i < lines.size(); ++i) {
        std::smatch m;
        if (std::regex_match(lines[i], m, scene_line)) {
            t.scene = m[1].str();
            t.particles = std::stoul(m[2].str());
        }
        if (lines[i].starts_with("pass ")) break;
    }
    if (i == lines.size()) throw std::runtime_error("no header line starting with \"pass\"");
    // Header titles are separated by runs of 2+ spaces ("min ms" holds one).
    static const std::regex gap(R"(\s{2,})");
    const std::string& h = lines[i];
    for (std::sregex_token_iterator it(h.begin(), h.end(), gap, -1), end; it != end; ++it)
        if (it->length() > 0) t.header.push_back(*it);
    for (++i; i < lines.size() && !lines[i].empty(); ++i) {
        std::istringstream in(lines[i]);
        std::vector<std::string> words;
        for (std::string w; in >> w;) words.push_back(w);
        if (words.size() < 7) throw std::runtime_error("short table row: " + lines[i]);
        const std::size_t n = words.size();
        if (!words[n - 1].ends_with("%")) throw std::runtime_error("share is not a percentage: " + lines[i]);
        Row r;
        for (std::size_t k = 0; k + 6 < n; ++k) r.name += (k ? " " : "") + words[k];
        r.calls = number(words[n - 6]);
        r.min = number(words[n - 5]);
        r.median = number(words[n - 4]);
        r.max = number(words[n - 3]);
        r.per_call = number(words[n - 2]);
        r.share = number(words[n - 1].substr(0, words[n - 1].size() - 1));
        t.rows.push_back(r);
    }
    return t;
}

// RFC 4180: fields separated by commas, optionally in double quotes with "" for a quote.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> row;
    std::string field;
    bool quoted = false, any = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        any = true;
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
            else if (c == '"') quoted = false;
            else field += c;
        } else if (c == '"') quoted = true;
        else if (c == ',') row.push_back(field), field.clear();
        else if (c == '\n') {
            row.push_back(field), field.clear();
            rows.push_back(row), row.clear();
            any = false;
        } else if (c != '\r') field += c;
    }
    if (any) row.push_back(field), rows.push_back(row);
    return rows;
}

bool contains(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

}  // namespace

TEST_CASE("ranryu profile prints one row per pass that ran with calls, min, median, max and share", "[cli][profile]") {
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"profile", "--scene", scene_file("small.json").string(), "--size", "64x48",
                                             "--frames", "4", "--warmup", "2"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, !Contains("GL error"));   // Debug builds report every GL error on stderr
    const Table t = parse_table(r.out);

    CHECK(t.header == std::vector<std::string>{"pass", "calls/fr", "min ms", "median ms", "max ms", "ms/call", "share"});
    CHECK(t.scene == "cli-small");
    CHECK(t.particles == 144);
    std::vector<std::string> names;
    for (const Row& row : t.rows) {
        INFO("row " << row.name);
        names.push_back(row.name);
        CHECK(row.calls > 0.0);   // only passes that ran are listed
        CHECK(row.min >= 0.0);
        CHECK(row.median >= 0.0);
        CHECK(row.max >= 0.0);
        CHECK(row.share >= 0.0);
    }
    for (const std::string& pass : kFramePasses) {
        INFO("pass " << pass);
        CHECK(contains(names, pass));
    }
    // Passes of other commands do not run here.
    CHECK_FALSE(contains(names, "readback"));
    CHECK_FALSE(contains(names, "present"));
    REQUIRE(!t.rows.empty());
    CHECK(t.rows.back().name == "frame (GPU span)");
    // Each listed pass once.
    CHECK(std::set<std::string>(names.begin(), names.end()).size() == names.size());
    // The draws run once a frame; the sim passes at least once.
    for (const Row& row : t.rows) {
        INFO("row " << row.name);
        if (row.name == "clear" || row.name.starts_with("draw-") || row.name == "frame (GPU span)") CHECK(row.calls == 1.0);
        if (row.name == "ballistic.integrate") CHECK(row.calls >= 1.0);
    }
    // No report files unless asked for.
    CHECK(list_dir(tmp.path()).empty());
}

TEST_CASE("ranryu profile --json and --csv write the same passes with device, driver, date, scene and particles",
          "[cli][profile]") {
    TempDir tmp;
    // Relative paths: resolved against the working folder.
    const Result r = run_ranryu(tmp.path(), {"profile", "--scene", scene_file("small.json").string(), "--size", "64x48",
                                             "--frames", "3", "--warmup", "1", "--json", "report.json", "--csv", "report.csv"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const Table t = parse_table(r.out);
    std::vector<std::string> table_passes;
    for (const Row& row : t.rows)
        if (row.name != "frame (GPU span)") table_passes.push_back(row.name);

    // Exactly the two files: no "*.tmp" left from the atomic write.
    CHECK(list_dir(tmp.path()) == std::vector<std::string>{"report.csv", "report.json"});

    // ---- JSON ----
    const nlohmann::json j = nlohmann::json::parse(read_file(tmp / "report.json"));
    INFO(j.dump(2));
    REQUIRE(j.is_object());
    for (const char* key : {"device", "driver", "date", "scene"}) {
        INFO("key " << key);
        REQUIRE(j.contains(key));
        REQUIRE(j[key].is_string());
        CHECK(!j[key].get<std::string>().empty());
    }
    CHECK(std::regex_match(j["date"].get<std::string>(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
    CHECK(j["scene"] == "cli-small");
    REQUIRE(j.contains("particles"));
    CHECK(j["particles"] == 144);
    CHECK(j["width"] == 64);
    CHECK(j["height"] == 48);
    CHECK(j["frames"] == 3);
    CHECK(j["warmup_frames"] == 1);
    // The table's first line is "RENDERER | DRIVER | DATE".
    CHECK_THAT(r.out, Contains(j["device"].get<std::string>() + " | " + j["driver"].get<std::string>()));

    REQUIRE(j.contains("passes"));
    REQUIRE(j["passes"].is_array());
    std::vector<std::string> json_passes;
    for (const auto& p : j["passes"]) {
        INFO(p.dump());
        REQUIRE(p.contains("name"));
        json_passes.push_back(p["name"].get<std::string>());
        for (const char* key : {"calls_per_frame", "min_ms", "median_ms", "max_ms", "ms_per_call", "share"}) {
            INFO("key " << key);
            REQUIRE(p.contains(key));
            REQUIRE(p[key].is_number());
            CHECK(p[key].get<double>() >= 0.0);
        }
        CHECK(p["calls_per_frame"].get<double>() > 0.0);
    }
    CHECK(json_passes == table_passes);
    for (const std::string& pass : kFramePasses) {
        INFO("pass " << pass);
        CHECK(contains(json_passes, pass));
    }

    // ---- CSV ----
    const auto csv = parse_csv(read_file(tmp / "report.csv"));
    REQUIRE(csv.size() >= 2);
    const std::vector<std::string>& header = csv[0];
    INFO("CSV header: " << read_file(tmp / "report.csv"));
    std::map<std::string, std::size_t> col;
    for (std::size_t k = 0; k < header.size(); ++k) col[header[k]] = k;
    for (const char* name : {"device", "driver", "date", "scene", "particles", "pass", "calls_per_frame", "min_ms",
                             "median_ms", "max_ms", "ms_per_call", "share"}) {
        INFO("CSV column " << name);
        REQUIRE(col.count(name));
    }
    std::vector<std::string> csv_passes;
    for (std::size_t i = 1; i < csv.size(); ++i) {
        const auto& row = csv[i];
        INFO("CSV row " << i);
        REQUIRE(row.size() == header.size());
        // The run's facts on every row, the same as in the JSON (the device name holds commas: quoted).
        CHECK(row[col["device"]] == j["device"].get<std::string>());
        CHECK(row[col["driver"]] == j["driver"].get<std::string>());
        CHECK(row[col["date"]] == j["date"].get<std::string>());
        CHECK(row[col["scene"]] == "cli-small");
        CHECK(row[col["particles"]] == "144");
        for (const char* name : {"calls_per_frame", "min_ms", "median_ms", "max_ms", "ms_per_call", "share"}) {
            INFO("CSV column " << name << " = " << row[col[name]]);
            double v = -1;
            CHECK_NOTHROW(v = number(row[col[name]]));
            CHECK(v >= 0.0);
        }
        if (row[col["pass"]] != "frame (GPU span)") csv_passes.push_back(row[col["pass"]]);
    }
    CHECK(csv_passes == json_passes);
}

TEST_CASE("ranryu profile lists the passes the scene does not run, and why, in its text and JSON", "[cli][profile]") {
    TempDir tmp;
    // The dam break with DFSPH, no turbulence, drawn as particles: the WCSPH passes, the turbulence's,
    // the sub-particles' and the surface's are not run, and the table has none of them.
    const Result r = run_ranryu(tmp.path(), {"profile", "--scene", "dam-break", "--spacing", "0.04", "--shading", "particles",
                                             "--size", "64x48", "--frames", "2", "--warmup", "1", "--json", "p.json", "--quiet"});
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    for (const char* line : {"not run: density, forces, integrate: WCSPH's, since the solver is dfsph",
                             "not run: wavelet, turbulence-force, since turbulence.amplitude is 0",
                             "not run: subparticles.*, since turbulence is off",
                             "not run: surface.anisotropy, surface.bounds, level-set.splat, level-set, mc.*, draw-surface, since the shading draws particles"})
        CHECK_THAT(r.out, Contains(line));
    CHECK_THAT(r.out, !Contains("not run: dfsph"));
    const auto j = nlohmann::json::parse(read_file(tmp.path() / "p.json"));
    REQUIRE(j["not_run"].is_array());
    std::set<std::string> listed, timed;
    for (const auto& s : j["not_run"]) listed.insert(s["passes"].get<std::string>());
    CHECK(listed.count("wavelet, turbulence-force"));
    for (const auto& p : j["passes"]) timed.insert(p["name"].get<std::string>());
    // Each entry's names as the timer names them (or a prefix and '*'), the text their list: none of
    // them took a sample.
    for (const auto& s : j["not_run"]) {
        REQUIRE(s["names"].is_array());
        std::string text;
        for (const auto& n : s["names"]) {
            const std::string name = n.get<std::string>();
            text += (text.empty() ? "" : ", ") + name;
            for (const std::string& t : timed) {
                INFO(name << " against the timed " << t);
                CHECK_FALSE((name == t || (name.ends_with('*') && t.starts_with(name.substr(0, name.size() - 1)))));
            }
        }
        CHECK(s["passes"].get<std::string>().starts_with(text));
    }
    for (const char* absent : {"wavelet", "turbulence-force", "level-set", "mc.emit", "draw-surface", "forces"}) CHECK_FALSE(timed.count(absent));
    CHECK(timed.count("dfsph.density"));
    // The scene's other named passes that did not run in the timed frames, listed apart: the boundary's
    // volumes and cells (at start-up), the rows' wall density (the first frame, in the warm-up), the
    // emitter (no emission in a profile).
    REQUIRE(j["not_timed"].is_string());
    const std::string untimed = j["not_timed"].get<std::string>();
    for (const char* name : {"boundary-volume", "boundary-cells", "dfsph.boundary.wall", "emit"}) {
        INFO(name);
        CHECK_THAT(untimed, Contains(name));
        CHECK_FALSE(timed.count(name));
    }
    CHECK_THAT(r.out, Contains("not timed: " + untimed + " ("));
    for (const char* named_elsewhere : {"dfsph.density", "wavelet", "pbf.lambda", "draw-particles"}) CHECK_THAT(untimed, !Contains(named_elsewhere));

    // The ballistic model (the falling block) runs none of SPH's passes and says so by their names;
    // its own integration is timed, under its own name.
    const Result b = run_ranryu(tmp.path(), {"profile", "--scene", "falling-block", "--shading", "particles", "--size", "64x48",
                                             "--frames", "2", "--warmup", "1", "--json", "b.json", "--quiet"});
    INFO(b.out << b.err);
    REQUIRE(b.exit_code == 0);
    CHECK_THAT(b.out, Contains("not run: hash, sort.*, reorder, density, forces, integrate, dfsph.*, pbf.*: the SPH model's, since the "
                               "scene uses the ballistic model, no SPH"));
    const auto jb = nlohmann::json::parse(read_file(tmp / "b.json"));
    std::set<std::string> ballistic_timed;
    for (const auto& p : jb["passes"]) ballistic_timed.insert(p["name"].get<std::string>());
    CHECK(ballistic_timed.count("ballistic.integrate"));
    for (const char* absent : {"hash", "reorder", "integrate", "density"}) CHECK_FALSE(ballistic_timed.count(absent));
    if (jb.contains("not_timed")) CHECK_THAT(jb["not_timed"].get<std::string>(), !Contains("hash") && !Contains("sort."));
}

TEST_CASE("ranryu profile prints a scene's sph.why, and says when --spacing or --solver changed the scene it speaks of",
          "[cli][profile]") {
    TempDir tmp;
    // The bundled dam break at a coarse spacing of its own, with a comment on its settings.
    auto scene = nlohmann::json::parse(read_file(source_dir() / "media" / "scenes" / "dam-break.json"));
    scene.erase("$schema");
    scene["particles"]["spacing"] = 0.04;
    const std::string why = "dfsph x1: the cheapest setting the sweep found sound (a test's words)";
    scene["sph"]["why"] = why;
    write_file(tmp / "commented.json", scene.dump());
    const std::vector<std::string> args = {"profile", "--scene", (tmp / "commented.json").string(), "--shading", "particles", "--size",
                                           "64x48", "--frames", "1", "--warmup", "0", "--quiet", "--json", "p.json"};
    const Result r = run_ranryu(tmp.path(), args);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("why its settings: " + why + "\n"));
    const auto j = nlohmann::json::parse(read_file(tmp / "p.json"));
    CHECK(j["settings_why"]["why"] == why);
    CHECK(j["settings_why"]["as_shipped"] == true);

    std::vector<std::string> other = args;
    other.insert(other.end(), {"--solver", "pbf"});
    const Result o = run_ranryu(tmp.path(), other);
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    CHECK_THAT(o.out, Contains("why its settings: " + why + " (said of the scene as shipped; --spacing or --solver changed it"));
    CHECK(nlohmann::json::parse(read_file(tmp / "p.json"))["settings_why"]["as_shipped"] == false);

    // A scene without one (the falling block: no SPH, no sph.why) prints no such line.
    const Result none = run_ranryu(tmp.path(), {"profile", "--scene", "falling-block", "--shading", "particles",
                                                "--size", "64x48", "--frames", "1", "--warmup", "0", "--quiet"});
    REQUIRE(none.exit_code == 0);
    CHECK_THAT(none.out, !Contains("why its settings"));
}

TEST_CASE("ranryu profile --overlay draws the window's panel offscreen as the pass \"overlay\" and times its CPU side",
          "[cli][profile][overlay]") {
    TempDir tmp;
    const std::vector<std::string> args = {"profile", "--scene", "dam-break", "--spacing", "0.04", "--shading", "particles",
                                           "--size", "320x240", "--frames", "3", "--warmup", "1", "--quiet"};
    std::vector<std::string> with = args;
    for (const char* a : {"--overlay", "--json", "o.json"}) with.push_back(a);
    const Result r = run_ranryu(tmp.path(), with);
    INFO(r.out << r.err);
    if (!RANRYU_HAVE_OVERLAY) {
        // A build without Dear ImGui refuses it, naming the option.
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains("--overlay"));
        return;
    }
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("overlay: CPU "));
    const auto j = nlohmann::json::parse(read_file(tmp.path() / "o.json"));
    bool timed = false;
    for (const auto& p : j["passes"])
        if (p["name"] == "overlay") {
            timed = true;
            CHECK(p["calls_per_frame"].get<double>() == 1.0);
            CHECK(p["ms_per_call"].get<double>() >= 0.0);
        }
    CHECK(timed);
    REQUIRE(j.contains("overlay"));
    CHECK(j["overlay"]["frames"] == 3);
    CHECK(j["overlay"]["cpu_ms_mean"].get<double>() > 0.0);   // building a panel takes the CPU some time
    CHECK(j["overlay"]["cpu_ms_max"].get<double>() >= j["overlay"]["cpu_ms_mean"].get<double>());

    // Without it: no such pass, no such line.
    const Result plain = run_ranryu(tmp.path(), args);
    REQUIRE(plain.exit_code == 0);
    CHECK_THAT(plain.out, !Contains("overlay"));
}

TEST_CASE("ranryu profile --records writes a frame's record a row, whose steps, iterations and least iteration step are the summary's",
          "[cli][profile]") {
    // The tank at rest at 0.025 m (480 particles) with DFSPH, 12 frames, none of warm-up: every frame's
    // StepState record (engine/profile/report.h record_csv_row()) is a row, and the JSON's simulation
    // summary is built from the same records: its steps are the rows' substeps, its iterations a step
    // the rows' density iterations over them, its issued iterations a step the rows' issued over them
    // (each at least what ran), its least_iteration_dt the least of the rows' iteration_dt
    // (docs/DFSPH.md (D8)), within the scene's largest step of 5 ms; each row's peak_error (the largest
    // particle error a density solve stopped with, (D6)) is at least its largest mean error, and the
    // summary's is the rows' largest. Where each frame's fastest and densest particles were lies in the
    // tank (media/scenes/hydrostatic.json: [0, 0.3] x [0, 0.4] x [0, 0.1] m), the densest in the column,
    // below its top at 0.25 m (a spacing's margin), and off the origin (what begin_frame resets them to).
    TempDir tmp;
    const Result r = run_ranryu(tmp.path(), {"profile", "--scene", "hydrostatic", "--solver", "dfsph", "--spacing", "0.025", "--size",
                                             "64x48", "--shading", "particles", "--frames", "12", "--warmup", "0", "--records",
                                             "records.csv", "--json", "report.json"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("the step the iterations allow (D8): least"));
    const auto csv = parse_csv(read_file(tmp / "records.csv"));
    REQUIRE(csv.size() == 13u);   // the header and a row a frame
    const std::vector<std::string>& head = csv[0];
    auto column = [&](const std::string& name) {
        const auto at = std::find(head.begin(), head.end(), name);
        REQUIRE(at != head.end());
        return std::size_t(at - head.begin());
    };
    const std::size_t steps_at = column("substeps"), iterations_at = column("iterations"), dt_at = column("iteration_dt"),
                      issued_at = column("issued"), peak_at = column("peak_error"), mean_at = column("max_error");
    const std::size_t fastest_at = column("fastest_x"), densest_at = column("densest_x");
    REQUIRE(column("fastest_y") == fastest_at + 1);
    REQUIRE(column("fastest_z") == fastest_at + 2);
    REQUIRE(column("densest_y") == densest_at + 1);
    REQUIRE(column("densest_z") == densest_at + 2);
    double steps = 0.0, iterations = 0.0, issued = 0.0, least = 1.0, peak = 0.0;
    for (std::size_t k = 1; k < csv.size(); ++k) {
        REQUIRE(csv[k].size() == head.size());
        const double dt = std::stod(csv[k][dt_at]);
        CHECK(dt > 0.0);
        CHECK(dt <= 0.005 * (1.0 + 1e-6));
        steps += std::stod(csv[k][steps_at]);
        iterations += std::stod(csv[k][iterations_at]);
        issued += std::stod(csv[k][issued_at]);
        CHECK(std::stod(csv[k][issued_at]) >= std::stod(csv[k][iterations_at]));   // what ran of what was issued
        least = std::min(least, dt);
        CHECK(std::stod(csv[k][peak_at]) >= std::stod(csv[k][mean_at]));
        peak = std::max(peak, std::stod(csv[k][peak_at]));
        const glm::dvec3 fastest(std::stod(csv[k][fastest_at]), std::stod(csv[k][fastest_at + 1]), std::stod(csv[k][fastest_at + 2]));
        const glm::dvec3 densest(std::stod(csv[k][densest_at]), std::stod(csv[k][densest_at + 1]), std::stod(csv[k][densest_at + 2]));
        INFO("frame " << k - 1 << ": fastest at " << fastest.x << ", " << fastest.y << ", " << fastest.z << "; densest at " << densest.x
                      << ", " << densest.y << ", " << densest.z);
        CHECK(glm::all(glm::greaterThanEqual(fastest, glm::dvec3(0.0))));
        CHECK(glm::all(glm::lessThanEqual(fastest, glm::dvec3(0.3, 0.4, 0.1))));
        CHECK(glm::all(glm::greaterThanEqual(densest, glm::dvec3(0.0))));
        CHECK(glm::all(glm::lessThanEqual(densest, glm::dvec3(0.3, 0.25 + 0.025, 0.1))));
        CHECK(glm::length(fastest) > 0.0);
        CHECK(glm::length(densest) > 0.0);
    }
    CHECK(peak > 0.0);
    const nlohmann::json s = nlohmann::json::parse(read_file(tmp / "report.json"))["simulation"];
    CHECK(s["steps"].get<double>() == steps);
    CHECK(s["iterations_per_step"].get<double>() == Approx(iterations / steps).epsilon(1e-12));
    CHECK(s["issued_iterations_per_step"].get<double>() == Approx(issued / steps).epsilon(1e-12));
    CHECK(s["least_iteration_dt"].get<double>() == Approx(least).epsilon(1e-6));
    CHECK(s["peak_density_error"].get<double>() == Approx(peak).epsilon(1e-6));
}

TEST_CASE("ranryu profile --detail times each solve's dispatches apart under it, as many a frame as the records issued; without it names them",
          "[cli][profile]") {
    // The tank at rest at 0.025 m with DFSPH (its density solve's rows eliminated, docs/DFSPH.md (D13)):
    // the density solve's residual pass runs once an issued iteration, so its calls a frame are the
    // records' issued iterations a step times the steps a frame, whether counted (no --detail: the line
    // "timed within their passes" and the JSON's untimed_within) or timed (--detail: a row indented under
    // "dfsph.pressure.solve", "within" in JSON and CSV). So are (D13)'s hand-off's.
    TempDir tmp;
    const std::vector<std::string> args = {"profile", "--scene", "hydrostatic", "--solver", "dfsph", "--spacing", "0.025",
                                           "--size", "64x48", "--shading", "particles", "--frames", "4", "--warmup", "0"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = args;
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    };
    const Result counted = run_ranryu(tmp.path(), with({"--json", "counted.json"}));
    const Result timed = run_ranryu(tmp.path(), with({"--detail", "--json", "timed.json", "--csv", "timed.csv"}));
    INFO(counted.describe() << "\n" << timed.describe());
    REQUIRE(counted.exit_code == 0);
    REQUIRE(timed.exit_code == 0);
    const nlohmann::json c = nlohmann::json::parse(read_file(tmp / "counted.json"));
    const nlohmann::json t = nlohmann::json::parse(read_file(tmp / "timed.json"));
    // Issued density iterations a frame, from the GPU's records (the same trajectory both times).
    auto issued_a_frame = [](const nlohmann::json& j) {
        const nlohmann::json& s = j.at("simulation");
        return s.at("issued_iterations_per_step").get<double>() * s.at("steps").get<double>() / s.at("frames").get<double>();
    };
    const double issued = issued_a_frame(c);
    REQUIRE(issued > 0.0);
    CHECK(issued_a_frame(t) == Approx(issued));

    CHECK_THAT(counted.out, Contains("timed within their passes, not apart (profile --detail times each):"));
    CHECK_THAT(counted.out, !Contains("  dfsph.pressure.correct "));
    CHECK(c.at("detail") == false);
    std::map<std::string, nlohmann::json> untimed;
    for (const auto& u : c.at("untimed_within")) untimed[u.at("name").get<std::string>()] = u;
    for (const char* name : {"dfsph.pressure.correct", "dfsph.pressure.hand-off"}) {
        INFO(name);
        REQUIRE(untimed.count(name) == 1);
        CHECK(untimed[name].at("within") == "dfsph.pressure.solve");
        CHECK(untimed[name].at("calls_per_frame").get<double>() == Approx(issued));
    }
    for (const auto& p : c.at("passes")) CHECK_FALSE(p.contains("within"));
    CHECK(c.at("not_timed").get<std::string>().find("dfsph.pressure.correct") == std::string::npos);

    CHECK(t.at("detail") == true);
    CHECK(t.at("untimed_within").empty());
    CHECK_THAT(timed.out, Contains("\n  dfsph.pressure.correct ") && Contains("\n  dfsph.pressure.accelerate ") &&
                              Contains("\n  dfsph.pressure.hand-off ") && Contains("\n  dfsph.pressure.extend "));
    const Table table = parse_table(timed.out);   // the notes on --detail come after the table's blank line
    std::map<std::string, Row> rows;
    for (const Row& r : table.rows) rows[r.name] = r;
    for (const char* name : {"dfsph.pressure.correct", "dfsph.pressure.hand-off"}) {
        INFO(name);
        REQUIRE(rows.count(name) == 1);
        CHECK(rows[name].calls == Approx(issued).epsilon(0.01));   // printed to two decimals
        const auto& passes = t.at("passes");
        const auto it = std::find_if(passes.begin(), passes.end(), [&](const nlohmann::json& p) { return p.at("name") == name; });
        REQUIRE(it != passes.end());
        CHECK(it->at("within") == "dfsph.pressure.solve");
        CHECK(it->at("calls_per_frame").get<double>() == Approx(issued));
        CHECK(it->at("ms_per_call").get<double>() >= 0.0);
    }
    const auto csv = parse_csv(read_file(tmp / "timed.csv"));
    REQUIRE(!csv.empty());
    REQUIRE(csv[0].back() == "within");
    bool found = false;
    for (const auto& row : csv)
        if (row.size() == csv[0].size() && row[8] == "dfsph.pressure.correct") {
            found = true;
            CHECK(row.back() == "dfsph.pressure.solve");
        }
    CHECK(found);
}

TEST_CASE("ranryu profile --detail names the surface's, the rasters' and the bitonic sort's small passes under their parents, and only those that run",
          "[cli][profile]") {
    // Each compute program has a pass of its own (docs/PERFORMANCE.md "Passes within passes, timed
    // apart"): place_grid within surface.bounds, the marching cubes' setup and scan within their
    // classify and compact, the compute raster's size, fill, rasterise and decode within shadow-map and
    // liquid-thickness (once a frame each), and the bitonic sort's local merge a pass of its own. With
    // the draw raster (RANRYU_WATER_RASTER=draw) only the fills run, and the compute raster's passes are
    // neither timed, nor counted, nor said to be "not timed".
    TempDir tmp;
    const std::vector<std::string> water = {"profile", "--scene", "hydrostatic", "--solver", "dfsph", "--spacing", "0.025", "--size",
                                            "64x48", "--shading", "water", "--frames", "2", "--warmup", "0"};
    auto with = [](std::vector<std::string> a, std::vector<std::string> extra) {
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    };
    const Result compute = run_ranryu(tmp.path(), with(water, {"--detail", "--json", "compute.json"}));
    RunOptions draw_raster;
    draw_raster.set_env = {{"RANRYU_WATER_RASTER", "draw"}};
    const Result draw = run_ranryu(tmp.path(), with(water, {"--json", "draw.json"}), draw_raster);
    write_file(tmp / "bitonic.json", R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
        "sph": {"solver": "dfsph", "sort": "bitonic"},
        "particles": {"spacing": 0.015, "blocks": [{"min": [0, 0, 0], "max": [0.24, 0.24, 0.24]}]}})");   // 4,096: past one tile
    // Particles by the impostors' compute raster (R15), which llvmpipe otherwise leaves to the draw.
    RunOptions impostor_compute;
    impostor_compute.set_env = {{"RANRYU_PARTICLE_RASTER", "compute"}};
    const Result bitonic = run_ranryu(tmp.path(), {"profile", "--scene", "bitonic.json", "--size", "64x48", "--shading", "particles",
                                                   "--frames", "2", "--warmup", "0", "--detail", "--json", "bitonic.json.out"},
                                      impostor_compute);
    INFO(compute.describe() << "\n" << draw.describe() << "\n" << bitonic.describe());
    REQUIRE(compute.exit_code == 0);
    REQUIRE(draw.exit_code == 0);
    REQUIRE(bitonic.exit_code == 0);
    auto rows = [](const nlohmann::json& j) {
        std::map<std::string, nlohmann::json> m;
        for (const auto& p : j.at("passes")) m[p.at("name").get<std::string>()] = p;
        return m;
    };
    const auto c = rows(nlohmann::json::parse(read_file(tmp / "compute.json")));
    const std::vector<std::pair<std::string, std::string>> within = {
        {"surface.place-grid", "surface.bounds"},     {"mc.setup", "mc.classify"},
        {"mc.scan", "mc.compact"},                    {"shadow-map.size", "shadow-map"},
        {"shadow-map.fill", "shadow-map"},            {"shadow-map.rasterise", "shadow-map"},
        {"shadow-map.decode", "shadow-map"},          {"liquid-thickness.fill", "liquid-thickness"},
        {"liquid-thickness.rasterise", "liquid-thickness"}, {"liquid-thickness.decode", "liquid-thickness"}};
    for (const auto& [name, parent] : within) {
        INFO(name);
        REQUIRE(c.count(name) == 1);
        CHECK(c.at(name).at("within") == parent);
        CHECK(c.at(name).at("calls_per_frame").get<double>() == Approx(1.0));
        REQUIRE(c.count(parent) == 1);
        CHECK_FALSE(c.at(parent).contains("within"));
    }

    const nlohmann::json d = nlohmann::json::parse(read_file(tmp / "draw.json"));
    const std::string not_timed = d.at("not_timed").get<std::string>();
    CHECK(not_timed.find("shadow-map.") == std::string::npos);
    CHECK(not_timed.find("liquid-thickness.") == std::string::npos);
    std::set<std::string> untimed;
    for (const auto& u : d.at("untimed_within")) untimed.insert(u.at("name").get<std::string>());
    CHECK(untimed.count("shadow-map.fill") == 1);
    CHECK(untimed.count("liquid-thickness.fill") == 1);
    for (const char* name : {"shadow-map.size", "shadow-map.rasterise", "shadow-map.decode", "liquid-thickness.rasterise"})
        CHECK(untimed.count(name) == 0);

    const auto b = rows(nlohmann::json::parse(read_file(tmp / "bitonic.json.out")));
    for (const char* name : {"sort.bitonic_local", "sort.bitonic_merge_local"}) {
        INFO(name);
        REQUIRE(b.count(name) == 1);
        CHECK_FALSE(b.at(name).contains("within"));
        CHECK(b.at(name).at("calls_per_frame").get<double>() > 0.0);
    }
    for (const char* name : {"draw-particles.fill", "draw-particles.rasterise", "draw-particles.resolve", "draw-particles.shade"}) {
        INFO(name);
        REQUIRE(b.count(name) == 1);
        CHECK(b.at(name).at("within") == "draw-particles");
        CHECK(b.at(name).at("calls_per_frame").get<double>() == Approx(1.0));
    }
    // The draw: no pass within draw-particles, timed or named.
    RunOptions impostor_draw;
    impostor_draw.set_env = {{"RANRYU_PARTICLE_RASTER", "draw"}};
    const Result drawn = run_ranryu(tmp.path(), {"profile", "--scene", "bitonic.json", "--size", "64x48", "--shading", "particles",
                                                 "--frames", "1", "--warmup", "0", "--detail", "--json", "drawn.json"},
                                    impostor_draw);
    INFO(drawn.describe());
    REQUIRE(drawn.exit_code == 0);
    const std::string drawn_text = read_file(tmp / "drawn.json");
    CHECK(drawn_text.find("\"draw-particles\"") != std::string::npos);
    CHECK(drawn_text.find("draw-particles.") == std::string::npos);
}
