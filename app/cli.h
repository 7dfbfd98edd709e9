#pragma once
// Command-line parsing for `ranryu COMMAND [options]`. Every mistake raises ranryu::InputError
// with one line naming the option and what is wrong (exit code 2).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ranryu::app {

struct Options {
    std::string command;          // run | record | profile | scenes | validate | export-field | help | version
    std::string case_name;        // validate: dam-break | hydrostatic
    std::optional<float> spacing; // particle spacing (m): the scene at another resolution
    std::string solver;           // run/record/profile/validate: dfsph | wcsph | pbf; empty: the scene's
    bool help = false;            // COMMAND --help

    std::string scene = "dam-break";
    bool scene_given = false;     // --scene was on the command line (validate: else the case's own)
    std::optional<int> frames;    // unset: the command's default
    std::optional<int> width, height;
    std::string out;              // record: output folder
    bool force = false;           // record: replace an earlier run in --out
    std::string screenshot;       // run: PNG of the window's last frame
    std::string script;           // run: timed input events to replay (input/script.h)
    std::string shots = "screenshots";   // run: folder of F12's (and the script's) screenshots
    std::string record_dir = "recordings";   // run: folder of F9's recordings, one take_NNN folder each
    std::string save_particles;   // run: FILE.ply|.vtp of the last frame's particles, written at exit
    std::optional<int> budget;    // run: the emitter's particle budget (default: the scene's count x 2)
    bool overlay = false;         // profile: draw the window's panel into the offscreen target too
    bool detail = false;          // profile: time apart the passes within others (profile::GpuTimer::set_detail)
    int warmup = 30;              // profile: frames run before timing
    std::string json, csv;        // profile: report files
    std::string records;          // record/profile: the simulation's per-frame records as CSV
    std::string checkpoint;       // record/profile: write the run's state here when it ends (frame/checkpoint.h)
    std::string resume;           // record/profile: go on from this checkpoint
    std::string shader_dir;       // read shaders from this folder instead of the embedded copies
    bool gl_debug = false;        // debug context + KHR_debug messages (always on in Debug builds)
    std::string shading;          // run/record/profile: water | fresnel | phong | gouraud | particles; empty: the scene's default
    bool export_mesh = false;     // record: frame_NNNNN.ply of the surface beside each PNG
    std::string export_particles; // record: ply | vtp: particles_NNNNN.EXT of the particles each frame
    std::string video;            // record: FILE.mp4|.webm|.gif made by ffmpeg from the frames
    bool no_png = false;          // record: no frame_NNNNN.png (with --video: the video only)
    bool quiet = false;           // record/profile/validate: no progress line on stderr
    bool schema = false;          // scenes: print the scene files' JSON Schema instead (docs/SCENES.md)
    bool markdown = false;        // scenes: print the scene keys' reference, docs/SCENES.md
    // export-field (app/export_field.cpp): the turbulence field y of docs/METHOD.md §4 on an N³ grid.
    int field_size = 64;          // --size N: grid points per axis
    float extent = 1.0f;          // --extent L (m): points at L·(i, j, k)/N
    int lmin = 2, lmax = 4;       // --octaves LMIN:LMAX
    float beta = 1.0f / 3.0f;     // --beta B: octave falloff 2^(-B(i-lmin)); 1/3: E(k) ~ k^(-5/3)
    std::uint32_t seed = 1;       // --seed S: the noise tiles' std::mt19937 seed
    // sweep (app/sweep.cpp): the grid of runs, empty for the defaults; --out is its folder.
    bool quick = false;                    // --quick: the small preset
    bool relax = false;                    // validate hydrostatic --relax: the relaxed start
    std::optional<float> settle, average;  // validate hydrostatic --settle S, --average S (simulated seconds)
    std::vector<std::string> cases, solvers;   // cases: validation case names, "scene:NAME", "scenes" expanded
    std::optional<float> seconds;          // --seconds S: the scene cases' simulated time (default 10)
    std::vector<float> spacings, factors;
    int shard_index = 1, shard_count = 1;  // --shard I/N: rows k with k mod N = I - 1
    bool list = false;                     // --list: print the rows, run none
};

Options parse(const std::vector<std::string>& args);

std::string usage();                                // ranryu --help
std::string command_help(const std::string& cmd);   // ranryu CMD --help

}  // namespace ranryu::app
