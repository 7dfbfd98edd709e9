#include "cli.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <cstdlib>
#include <map>
#include <set>

#include "core/error.h"
#include "record/particle_files.h"
#include "input/commands.h"
#include "validation/cases.h"

namespace ranryu::app {
namespace {

// Which options each command takes.
const std::map<std::string, std::set<std::string>> kAccepts = {
    {"run", {"--scene", "--spacing", "--solver", "--frames", "--size", "--screenshot", "--script", "--shots", "--shading",
             "--record-dir", "--save-particles", "--budget", "--shader-dir", "--gl-debug"}},
    {"record", {"--scene", "--spacing", "--solver", "--frames", "--size", "--out", "--force", "--shading", "--export-mesh",
                "--export-particles", "--video", "--no-png", "--records", "--quiet", "--shader-dir", "--gl-debug", "--checkpoint",
                "--resume"}},
    {"profile", {"--scene", "--spacing", "--solver", "--frames", "--size", "--warmup", "--json", "--csv", "--records",
                 "--shading", "--overlay", "--detail", "--quiet", "--shader-dir", "--gl-debug", "--checkpoint", "--resume"}},
    {"scenes", {"--schema", "--markdown"}},
    {"validate", {"--scene", "--spacing", "--solver", "--json", "--quiet", "--shader-dir", "--gl-debug", "--relax", "--settle", "--average"}},
    {"sweep", {"--out", "--quick", "--cases", "--solvers", "--spacings", "--factors", "--seconds", "--shard", "--list", "--quiet",
               "--shader-dir", "--gl-debug"}},
    {"export-field", {"--size", "--extent", "--octaves", "--beta", "--seed", "--out", "--force", "--shader-dir", "--gl-debug"}},
};
const std::set<std::string> kFlags = {"--force", "--gl-debug", "--export-mesh", "--no-png", "--quick", "--list", "--quiet", "--relax", "--schema", "--markdown",
                                      "--overlay", "--detail"};

int parse_int(const std::string& option, const std::string& text, int lo, int hi) {
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size())
        throw InputError(option + " " + text + ": not a whole number");
    if (v < lo || v > hi)
        throw InputError(option + " " + text + ": out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
}

float parse_float(const std::string& option, const std::string& text, float lo, float hi, const std::string& what) {
    char* end = nullptr;
    const float v = std::strtof(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !(v >= lo && v <= hi))
        throw InputError(option + " " + text + ": expected " + what);
    return v;
}

// "a,b,c" into its items; an empty item is a mistake.
std::vector<std::string> split_list(const std::string& option, const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        out.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (out.back().empty()) throw InputError(option + " " + text + ": expected a comma-separated list with no empty item");
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

}  // namespace

Options parse(const std::vector<std::string>& args) {
    Options o;
    if (args.empty()) throw InputError("no command given (try: ranryu --help)");
    const std::string& first = args[0];
    if (first == "--help" || first == "-h" || first == "help") {
        o.command = "help";
        return o;
    }
    if (first == "--version") {
        o.command = "version";
        return o;
    }
    if (!kAccepts.count(first))
        throw InputError("unknown command \"" + first + "\" (commands: run, record, profile, scenes, validate, sweep, export-field)");
    o.command = first;
    const auto& accepts = kAccepts.at(first);
    for (std::size_t i = 1; i < args.size(); ++i) {
        std::string opt = args[i], value;
        if (opt == "--help" || opt == "-h") {
            o.help = true;
            continue;
        }
        const auto eq = opt.find('=');
        const bool inline_value = opt.starts_with("--") && eq != std::string::npos;
        if (inline_value) {
            value = opt.substr(eq + 1);
            opt = opt.substr(0, eq);
        }
        // Name the option's own mistake first: an unknown option is unknown wherever it stands.
        if (first == "validate" && !opt.starts_with("--") && o.case_name.empty()) {
            o.case_name = opt;
            continue;
        }
        if (!opt.starts_with("--")) throw InputError("unexpected argument \"" + opt + "\" for ranryu " + first);
        if (!accepts.count(opt))
            throw InputError("unknown option " + opt + " for ranryu " + first + " (see ranryu " + first + " --help)");
        if (kFlags.count(opt)) {
            if (inline_value) throw InputError(opt + "=" + value + ": " + opt + " takes no value");
        } else if (!inline_value) {
            if (i + 1 >= args.size()) throw InputError(opt + ": needs a value");
            value = args[++i];
        }
        if (!kFlags.count(opt) && value.empty()) throw InputError(opt + ": needs a value");
        if (opt == "--scene") o.scene = value, o.scene_given = true;
        else if (opt == "--frames") o.frames = parse_int(opt, value, first == "run" ? 0 : 1, 1'000'000);
        else if (opt == "--size" && first == "export-field") o.field_size = parse_int(opt, value, 8, 256);
        else if (opt == "--extent") o.extent = parse_float(opt, value, 1e-6f, 1e6f, "an extent in metres in [1e-6, 1e6]");
        else if (opt == "--beta") o.beta = parse_float(opt, value, 0.0f, 4.0f, "an octave falloff exponent in [0, 4]");
        else if (opt == "--seed") {
            std::uint32_t v = 0;
            const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
            if (ec != std::errc() || end != value.data() + value.size())
                throw InputError("--seed " + value + ": expected a whole number in [0, 4294967295]");
            o.seed = v;
        } else if (opt == "--octaves") {
            const auto colon = value.find(':');
            try {
                if (colon == std::string::npos) throw InputError("");
                o.lmin = parse_int(opt, value.substr(0, colon), -8, 16);
                o.lmax = parse_int(opt, value.substr(colon + 1), -8, 16);
            } catch (const InputError&) {
                throw InputError("--octaves " + value + ": expected LMIN:LMAX, whole numbers in [-8, 16]");
            }
            if (o.lmin > o.lmax) throw InputError("--octaves " + value + ": LMIN must not exceed LMAX");
        } else if (opt == "--size") {
            const auto x = value.find('x');
            if (x == std::string::npos) throw InputError("--size " + value + ": expected WIDTHxHEIGHT, e.g. 960x540");
            const std::string w = value.substr(0, x), h = value.substr(x + 1);
            int wv = 0, hv = 0;
            try {
                wv = parse_int("--size", w, 16, 8192);
                hv = parse_int("--size", h, 16, 8192);
            } catch (const InputError&) {
                throw InputError("--size " + value + ": width and height must be whole numbers in [16, 8192]");
            }
            o.width = wv;
            o.height = hv;
        } else if (opt == "--spacing") {
            char* end = nullptr;
            const float dx = std::strtof(value.c_str(), &end);
            if (end != value.c_str() + value.size() || !(dx >= 1e-4f && dx <= 1.0f))
                throw InputError("--spacing " + value + ": expected a particle spacing in metres in [0.0001, 1]");
            o.spacing = dx;
        } else if (opt == "--solver") {
            if (value != "dfsph" && value != "wcsph" && value != "pbf") throw InputError("--solver " + value + ": expected dfsph, wcsph or pbf");
            o.solver = value;
        } else if (opt == "--out") o.out = value;
        else if (opt == "--force") o.force = true;
        else if (opt == "--screenshot") o.screenshot = value;
        else if (opt == "--script") o.script = value;
        else if (opt == "--shots") o.shots = value;
        else if (opt == "--record-dir") o.record_dir = value;
        else if (opt == "--save-particles") {
            const std::string ext = std::filesystem::path(value).extension().string();
            if (ext != ".ply" && ext != ".vtp") throw InputError("--save-particles " + value + ": expected a file name ending in .ply or .vtp");
            o.save_particles = value;
        } else if (opt == "--budget") o.budget = parse_int(opt, value, 1, 64'000'000);
        else if (opt == "--overlay") o.overlay = true;
        else if (opt == "--detail") o.detail = true;
        else if (opt == "--warmup") o.warmup = parse_int(opt, value, 0, 100'000);
        else if (opt == "--json") o.json = value;
        else if (opt == "--csv") o.csv = value;
        else if (opt == "--records") o.records = value;
        else if (opt == "--checkpoint") o.checkpoint = value;
        else if (opt == "--resume") o.resume = value;
        else if (opt == "--shader-dir") o.shader_dir = value;
        else if (opt == "--gl-debug") o.gl_debug = true;
        else if (opt == "--export-mesh") o.export_mesh = true;
        else if (opt == "--export-particles") {
            record::parse_particle_format(value, opt);   // checked here, before any work
            o.export_particles = value;
        } else if (opt == "--video") o.video = value;
        else if (opt == "--no-png") o.no_png = true;
        else if (opt == "--quiet") o.quiet = true;
        else if (opt == "--quick") o.quick = true;
        else if (opt == "--relax") o.relax = true;
        else if (opt == "--settle") o.settle = parse_float(opt, value, 0.0f, 60.0f, "simulated seconds in [0, 60]");
        else if (opt == "--average") o.average = parse_float(opt, value, 0.05f, 60.0f, "simulated seconds in [0.05, 60]");
        else if (opt == "--list") o.list = true;
        else if (opt == "--cases") {
            // The validation cases, and the scene cases: "scene:NAME" of a bundled SPH scene, or
            // "scenes" for all of them (validation/cases.h), expanded here in `ranryu scenes` order.
            o.cases.clear();
            for (const std::string& n : split_list(opt, value)) {
                if (n == "scenes") {
                    for (const std::string& c : validation::scene_cases()) o.cases.push_back(c);
                    continue;
                }
                try {
                    validation::case_scene(n);
                } catch (const InputError& e) {
                    throw InputError("--cases " + value + ": " + e.what());
                }
                o.cases.push_back(n);
            }
            std::set<std::string> seen;
            for (const std::string& n : o.cases)
                if (!seen.insert(n).second) throw InputError("--cases " + value + ": case \"" + n + "\" named twice");
        } else if (opt == "--solvers") {
            o.solvers = split_list(opt, value);
            for (const std::string& n : o.solvers)
                if (n != "dfsph" && n != "wcsph" && n != "pbf")
                    throw InputError(opt + " " + value + ": unknown solver \"" + n + "\" (dfsph, wcsph, pbf)");
        } else if (opt == "--seconds") {
            o.seconds = parse_float(opt, value, 0.0f, 3600.0f, "simulated seconds in (0, 3600]");
            if (!(*o.seconds > 0.0f)) throw InputError("--seconds " + value + ": expected simulated seconds in (0, 3600]");
        } else if (opt == "--spacings" || opt == "--factors") {
            std::vector<float>& numbers = opt == "--spacings" ? o.spacings : o.factors;
            numbers.clear();
            for (const std::string& n : split_list(opt, value))
                numbers.push_back(opt == "--spacings" ? parse_float(opt, n, 1e-4f, 1.0f, "spacings in metres in [0.0001, 1], comma-separated")
                                                      : parse_float(opt, n, 0.01f, 20.0f, "time-step factors in [0.01, 20], comma-separated"));
        } else if (opt == "--shard") {
            const auto slash = value.find('/');
            try {
                if (slash == std::string::npos) throw InputError("");
                o.shard_index = parse_int(opt, value.substr(0, slash), 1, 1'000'000);
                o.shard_count = parse_int(opt, value.substr(slash + 1), 1, 1'000'000);
            } catch (const InputError&) {
                throw InputError("--shard " + value + ": expected I/N, whole numbers with 1 <= I <= N");
            }
            if (o.shard_index > o.shard_count) throw InputError("--shard " + value + ": expected I/N with 1 <= I <= N");
        }
        else if (opt == "--schema") o.schema = true;
        else if (opt == "--markdown") o.markdown = true;
        else if (opt == "--shading") {
            // The names of render::Shading (engine/render/renderer.h); kept here so parsing needs no GL.
            if (value != "water" && value != "fresnel" && value != "phong" && value != "gouraud" && value != "particles")
                throw InputError("--shading " + value + ": expected one of water, fresnel, phong, gouraud, particles");
            o.shading = value;
        }
    }
    if (o.command == "validate" && o.case_name.empty() && !o.help)
        throw InputError(std::string("validate: name a case (") + validation::kCaseList + ")");
    if (o.relax && o.case_name != "hydrostatic") throw InputError("--relax: only the hydrostatic case relaxes its start");
    if ((o.settle || o.average) && o.case_name != "hydrostatic")
        throw InputError(std::string(o.settle ? "--settle" : "--average") + ": only the hydrostatic case settles and averages");
    if (o.command == "sweep" && o.out.empty() && !o.help && !o.list) throw InputError("--out: sweep needs --out DIR for its rows");
    if (o.seconds && std::none_of(o.cases.begin(), o.cases.end(), validation::is_scene_case))
        throw InputError("--seconds: only the scene cases (--cases scene:NAME or scenes) run for a given time; the validation cases "
                         "run their own length");
    if (o.schema && o.markdown) throw InputError("--schema, --markdown: give one of them");
    if (o.command == "export-field" && o.out.empty() && !o.help)
        throw InputError("--out: export-field needs --out FILE.npy");
    return o;
}

std::string usage() {
    return R"(ranryu - real-time SPH liquid with sub-particle turbulence, on OpenGL 4.3 compute shaders

usage: ranryu COMMAND [options]      (ranryu COMMAND --help for its options)

commands:
  run       watch a scene in a window
  record    render a scene headless to frame_00000.png, ... and run.json (and a video, particle files)
  profile   run a scene headless and print per-pass GPU timings
  scenes    list the bundled scenes (--schema, --markdown: the scene keys' schema or reference)
  validate  run a validation case (dam-break, hydrostatic, standing-wave, impact-pressure, obstacle-impact) against its reference
  sweep     run the validation cases over solver x spacing x time-step factor: accuracy against cost
  export-field  sample the turbulence field (curl of wavelet noise) on a grid to a .npy file

  --version   print the version and the commit it was built from
  --help      this text

record, profile and validate show their progress on stderr (--quiet: none): a line rewritten in
place on a terminal, else a plain line every 10 s (RANRYU_PROGRESS_SECONDS sets the interval).
Ctrl-C (SIGINT) or SIGTERM stops a run after the frame in progress; a second one, a second or more
later, ends it at once.

exit codes: 0 success, 1 failure, 2 bad input (usage, scene, parameter, output folder),
            3 the simulation went unstable (reported with the step and the cause),
            130 stopped by SIGINT or SIGTERM (record: the frames so far and run.json are written)
)";
}

std::string command_help(const std::string& cmd) {
    const std::string common = R"(  --scene NAME|FILE   bundled scene name or path to a scene .json (default dam-break)
  --spacing DX        particle spacing in metres: the scene at another resolution
  --solver NAME       dfsph | wcsph | pbf: the SPH pressure solver (default: the scene's, dfsph unless
                      it says otherwise; docs/DFSPH.md, docs/SPH.md, docs/PBF.md)
  --size WxH          image size in pixels, 16..8192 each (default: the scene's)
  --shading MODE      water | fresnel | phong | gouraud | particles: how the liquid is drawn
                      (default: water for SPH scenes, particles for ballistic ones; the surface
                      modes mesh the SPH liquid each frame; docs/RENDERING.md)
  --shader-dir DIR    read shaders from DIR instead of the copies built into the binary
  --gl-debug          debug context; print the driver's KHR_debug messages
)";
    if (cmd == "run")
        return "usage: ranryu run [options]\n\nWatch a scene in a window: drag to orbit, wheel to zoom. A panel shows fps, GPU ms a\n"
               "frame, the real-time factor, particles, substeps, solver iterations, the guard and a bar per GPU\n"
               "pass, with the controls (pause, step, reset, shading, scene, solver, spacing: a change of these\n"
               "restarts the scene; viscosity, time-step factor, turbulence on/off and amplitude: live).\n\n"
               "In an SPH scene, P puts in the paddle, a sphere of a tenth of the tank's largest extent (at least\n"
               "3 spacings) that the right mouse button drags through the liquid in the plane facing the camera;\n"
               "it pushes the liquid and never lets it through, and follows the drag at most a quarter spacing a\n"
               "substep and half the scene's speed estimate sqrt(2 g H). E pours liquid in from a nozzle over the\n"
               "tank, one sheet a frame, up to the particle budget (--budget; default twice the scene's\n"
               "particles, all allocated at start); the panel states the budget and the live count.\n\nkeys:\n" +
               input::keys_help() + "\n" + common +
               R"(  --frames N          quit after N frames (default 0: run until the window closes)
  --screenshot FILE   save the window's last frame as PNG (with --frames, for tests)
  --shots DIR         folder for F12's screenshots, shot_00000.png, ... (default screenshots; created
                      when the first is taken; an existing file is never replaced)
  --record-dir DIR    folder for F9's recordings (default recordings): each take goes to the first
                      take_NNN that does not exist, as frame_00000.png, ... of the picture (without
                      the panel), written by the same asynchronous writer as `ranryu record`
  --budget N          the emitter's particle budget: the scene's particles and those it may pour in
                      (default twice the scene's; all allocated at start)
  --save-particles FILE
                      at the end, write the last frame's particles to FILE (.ply or .vtp; an
                      existing file is refused)
  --script FILE       replay timed input from FILE, one event a line (FRAME is the frame, from 0,
                      before which it acts; frames never decrease; # starts a comment):
                        FRAME key NAME            space n r m t p e h f12 f9 escape 1-9
                        FRAME drag DX DY          a mouse drag of DX, DY pixels (orbit)
                        FRAME paddle DX DY        a right-button drag of DX, DY pixels (the paddle)
                        FRAME wheel N             N notches of the wheel (zoom)
                        FRAME panel ACTION [ARG]  the panel's widgets: pause on|off, step, reset,
                                                  screenshot, quit, panel on|off, shading MODE,
                                                  scene NAME, solver dfsph|wcsph|pbf,
                                                  turbulence on|off, amplitude A (1/m),
                                                  viscosity NU (m^2/s), cfl C, paddle on|off,
                                                  emitter on|off, record on|off, spacing DX (m)
                      a mistake is reported as FILE:LINE (exit 2); the script does not end the run:
                      end it with "key escape" or "panel quit" (or --frames)
)";
    if (cmd == "record")
        return "usage: ranryu record [options]\n\nRender a scene offscreen and write frame_00000.png, ... and run.json (scene, size,\n"
               "frames, simulated time per frame, per-pass GPU timings) into --out, then print the timing table.\n"
               "Ctrl-C (or SIGTERM) stops it after the frame in progress: every frame so far is written, and\n"
               "run.json says \"interrupted\": true and the frame it stopped at (exit code 130).\n\n" +
               common +
               R"(  --frames N          frames to record (default 120)
  --out DIR           output folder (default out/SCENE); created if missing
  --force             replace an earlier run in DIR (otherwise refused)
  --export-mesh       also write the surface of each frame as frame_00000.ply, ... (binary PLY:
                      marching cubes' triangles with normals, 3 vertices each; needs a surface
                      shading of an SPH scene)
  --export-particles FORMAT
                      also write each frame's particles as particles_00000.FORMAT, ...: ply (binary
                      PLY point cloud: Blender, Houdini) or vtp (VTK PolyData: ParaView), with
                      position, velocity, density, pressure and, with sub-particles, level and energy
  --video FILE        also make a video of the frames with ffmpeg (which must be installed): .mp4
                      (H.264), .webm (VP9) or .gif, at the scene's frame rate; an existing FILE is
                      refused unless --force
  --no-png            write no frame_*.png (with --video: only the video)
  --records FILE      also write the SPH simulation's record of every frame as CSV (time, steps,
                      dt, speeds, density, solver iterations and errors, the guard's counts)
  --checkpoint FILE   when the run ends (done, or stopped by Ctrl-C or SIGTERM: a batch job's time
                      limit), write its state to FILE, to go on from with --resume (replaces FILE;
                      not written after an instability)
  --resume FILE       go on from a checkpoint: its scene, spacing and solver (so no --scene,
                      --spacing or --solver), frame numbers from its last frame on; --frames N more
                      into the same --out: the earlier frames and run.json stay, this run's
                      report is run_from_NNNNN.json (a --video is this run's frames only)
  --quiet             no progress line on stderr
)";
    if (cmd == "profile")
        return "usage: ranryu profile [options]\n\nRun a scene headless for N frames and print, per GPU pass: calls per frame,\n"
               "min / median / max ms per frame and share of the frame.\n\n" + common +
               R"(  --frames N          frames to time (default 300)
  --warmup N          frames run before timing starts (default 30)
  --json FILE         also write the report as JSON (device, driver, date, scene, particles, passes)
  --csv FILE          also write it as CSV, one row per pass
  --records FILE      also write the SPH simulation's record of every frame as CSV (warm-up included)
  --overlay           also draw the window's panel (Dear ImGui) into the picture each frame: its GPU
                      time is the pass "overlay", its CPU time the line "overlay: CPU ... ms a frame"
                      (builds without Dear ImGui refuse it)
  --detail            also time apart each dispatch of the passes that run within others (a solve's
                      accelerate and correct passes, indented under it); the timestamps around each
                      dispatch add GPU time, so fps and shares are those of a slower frame
  --checkpoint FILE   when the run ends (done, or stopped by Ctrl-C or SIGTERM: a batch job's time
                      limit), write its state to FILE, to go on from with --resume (replaces FILE;
                      not written after an instability)
  --resume FILE       go on from a checkpoint: its scene, spacing and solver (so no --scene,
                      --spacing or --solver), frame numbers from its last frame on: --warmup
                      frames, then --frames N more timed
  --quiet             no progress line on stderr
)";
    if (cmd == "scenes")
        return R"(usage: ranryu scenes [--schema | --markdown]

List the bundled scenes with their descriptions, and under a scene whose file says why its solver and
step settings are its own (sph.why, docs/SCENES.md) that line.

  --schema            print instead the JSON Schema of scene files (media/scenes/scene.schema.json)
  --markdown          print instead the reference of every scene key (docs/SCENES.md)
)";
    if (cmd == "validate")
        return R"(usage: ranryu validate CASE [options]

Run a case headless and print the simulation next to its reference, with the error.
  dam-break     surge front Z = z/a against T = t sqrt(2g/a), next to Martin & Moyce (1952)
  hydrostatic   pressure against depth next to rho0 g (H - z), and the spurious velocity
  standing-wave the first sloshing mode's period against linear theory, and its decay
  impact-pressure
                the pressure of the surge on the wall it strikes, at three heights, next to
                Lobovsky et al. (2014): the impact's time, the peak, the run-up after it
  obstacle-impact
                the same on the face of a box the surge strikes, next to Kleefsman et al.
                (2005), SPHERIC's test 2

  --scene FILE        the case's scene from a file instead of the bundled one of its name (to vary
                      its settings, e.g. "sph": {"boundary_viscosity": 1e-3} for no-slip walls)
  --spacing DX        particle spacing in metres (default: the scene's)
  --solver NAME       dfsph | wcsph | pbf (default: the scene's)
  --json FILE         also write the series and errors as JSON
  --relax             hydrostatic: first relax the block at rest (velocities zeroed after each frame,
                      up to 2 s) and start the clock from there (docs/VALIDATION.md "The relaxed start")
  --settle S          hydrostatic: simulated seconds run before the pressure is measured (default 1)
  --average S         hydrostatic: simulated seconds the pressure is averaged over (default 0.5); each
                      half second's errors are printed on their own as well
  --quiet             no progress line on stderr
  --shader-dir DIR    read shaders from DIR instead of the copies built into the binary
  --gl-debug          debug context; print the driver's KHR_debug messages
)";
    if (cmd == "sweep")
        return R"(usage: ranryu sweep --out DIR [options]

Run the validation cases headless over case x solver x spacing x time-step factor and record, one
row a run, the accuracy (the case's error against its reference, the mean and max density
deviation, the energy drift) and the cost (GPU ms per simulated second, wall seconds), or the guard's
verdict when the run went unstable (frame, time, cause), or "energy gain" when it ran to the end
having made more than 1 % of its energy (not where the turbulence force does work on the fluid). The
rows go to sweep.json and sweep.csv in DIR after each run; a second invocation with the same DIR
skips the rows already there (docs/SWEEP.md).
Charts: scripts/sweep-charts.py DIR --out CHARTS (accuracy against cost, and the stability map).
A scene's cheapest sound setting: scripts/scene-settings.py DIR (docs/SWEEP.md "Choosing a scene's
settings").

  --out DIR           the sweep's folder (made if missing)
  --quick             the small preset: dam-break and hydrostatic, dfsph and wcsph, spacings 0.04 and
                      0.025 m, factors 1 and 10 (wcsph at 10 goes unstable): a first look in a minute
  --cases LIST        dam-break,hydrostatic,standing-wave (default all three), impact-pressure and
                      obstacle-impact (the pressure after the impact, error the sensors' mean rms), and the scene cases:
                      scene:NAME runs the bundled SPH scene NAME as it is for --seconds, checked for
                      stability and compression (no reference); scenes names every bundled SPH scene
  --solvers LIST      dfsph,wcsph,pbf (default all three; --quick: dfsph,wcsph)
  --spacings LIST     spacings in metres (default: each validation case's own spacing and half of
                      it; a scene case's own spacing)
  --factors LIST      time-step factors: each multiplies every bound on the step, the Courant number
                      (sph.cfl, and DFSPH's sph.dfsph_cfl where set), the force condition's
                      sph.force_factor and the largest step
                      sph.max_time_step (docs/SPH.md (7), docs/DFSPH.md (D8)); for pbf, whose step
                      is fixed, the substeps a frame are divided by it (docs/SWEEP.md); default
                      0.5,1,1.5,2
  --seconds S         the scene cases' simulated seconds (default 10); a folder's rows must have run
                      as long to be resumed
  --shard I/N         run only rows k with k mod N = I - 1 (k counts from 0 in the order --list
                      prints): one shard a job of a Slurm array or GNU parallel, each with its own --out
  --list              print the rows (and which are done) without running any
  --quiet             no progress line on stderr
  --shader-dir DIR    read shaders from DIR instead of the copies built into the binary
  --gl-debug          debug context; print the driver's KHR_debug messages
)";
    if (cmd == "export-field")
        return R"(usage: ranryu export-field --out FILE.npy [options]

Sample the turbulence field y(x) = sum_{i=LMIN}^{LMAX} w(2^i x + o_i) 2^(-B (i - LMIN)) (METHOD.md
section 4; w = analytic curl of wavelet noise on 32^3 tiles, a tile cell of octave 0 is 1 m, o_i a
fixed per-octave offset) at the points L (i, j, k) / N,
0 <= i, j, k < N, and write it as a NumPy .npy v1.0 file of float32, shape (N, N, N, 3), C order:
f[i, j, k] is y at (x_i, y_j, z_k).

  --size N            grid points per axis, 8..256 (default 64)
  --extent L          side of the sampled cube in metres (default 1)
  --octaves LMIN:LMAX octaves summed (default 2:4)
  --beta B            amplitude falloff per octave (default 1/3: shell-averaged E(k) ~ k^(-5/3);
                      5/6 gives energy per octave ~ k^(-5/3), Kim et al. 2008)
  --seed S            seed of the noise tiles (default 1)
  --out FILE.npy      output file (required); written atomically
  --force             replace FILE.npy if it exists (otherwise refused)
  --shader-dir DIR    read shaders from DIR instead of the copies built into the binary
  --gl-debug          debug context; print the driver's KHR_debug messages
)";
    return usage();
}

}  // namespace ranryu::app
