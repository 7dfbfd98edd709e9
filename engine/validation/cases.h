#pragma once
// Validation cases: the simulation run headless against a published experiment or an analytic
// solution, with the error. `ranryu validate` prints them; tests assert bounds on them.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "core/error.h"
#include "gl/objects.h"
#include "gl/readback.h"
#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/program.h"
#include "shader/source.h"

namespace ranryu::frame {
class Progress;
}

namespace ranryu::validation {

// Each case runs the shared frame loop; with a `progress`, it sets the run's length and shows its
// line. Throws sim::UnstableError, or frame::interrupted() when SIGINT or SIGTERM stopped the run.

// What every case measures besides its own error, for the speed/accuracy sweep (ranryu sweep): the
// density's deviation, the energy's drift and the run's cost.
struct RunStats {
    double max_density_deviation = 0.0;    // max over frames and particles of rho/rho0 - 1 (the guard's records)
    double mean_density_deviation = 0.0;   // mean over particles of max(rho/rho0 - 1, 0) at the end: the compression
    // E = sum of |v|^2/2 + |g| (y - floor) per unit mass, at the start and the end (J/kg); the drift
    // (E_end - E_start)/E_start: negative where the flow dissipates, positive where energy is made.
    double energy_start = 0.0, energy_end = 0.0, energy_drift = 0.0;
    double simulated_seconds = 0.0;
    double gpu_ms = 0.0;                   // the frames' GPU spans, summed (any the timer skipped at the timed ones' mean)
    double gpu_ms_per_simulated_second = 0.0;
    int guard_spikes = 0;                  // frames past the guard's density or speed bound that it let pass (sim/guard.h)
};

// Martin & Moyce (1952), n^2 = 2: surge front Z = z/a against T = t sqrt(2g/a).
struct DamBreakResult {
    double a = 0.0, wall = 0.0, spacing = 0.0;
    std::size_t particles = 0;
    std::vector<std::pair<double, double>> simulated;   // (T, Z) per frame, from the GPU's records
    struct Point { double t, measured, simulated; };
    std::vector<Point> compared;                        // at the experiment's times
    double rms_error = 0.0, max_error = 0.0;            // in Z
    std::uint64_t steps = 0;                            // the solver's steps over the run
    double seconds = 0.0;                               // the run on the wall clock
    RunStats stats;
};
DamBreakResult dam_break(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress = nullptr);

// The tank's start relaxed before the case's clock starts (docs/VALIDATION.md "Tank at rest", "The
// relaxed start"): the lattice the scene places is no equilibrium beside the walls. The block is run
// with the scene's solver a frame at a time, its velocities set to zero after every frame, until a
// frame begun at rest (not the first) ends with an rms speed at or below `rms_speed` (m/s), or
// `max_frames` frames have run (then the result says it was not reached). The speeds and positions
// come back asynchronously, frames late (ParticleSnapshots), so a few more frames from rest may run
// after the one that met the bound; the relaxed start is that frame's positions, and the result counts
// the frames and steps up to it, so neither depends on when the snapshots came back. The measured run
// starts from the relaxed positions at rest in a fresh pipeline: time 0, the solver's warm starts and
// records fresh. max_frames = 0: the lattice start as it is.
struct Relaxation {
    int max_frames = 0;
    double rms_speed = 0.0;
    bool late_snapshots = false;   // tests: the snapshots handed over as late as they can be (ParticleSnapshots::hand_over_late)
};
// The relaxation `ranryu validate hydrostatic` uses: at most 2 s of frames, and the bound rms_speed =
// 0.01 g frame_dt of a frame begun at rest (an unbalanced acceleration of 1 % of g in rms,
// docs/VALIDATION.md "The relaxed start").
Relaxation hydrostatic_relaxation(const scene::Scene& scene);

// A tank at rest after `settle_s` seconds from its (relaxed) start: pressure in layers one spacing
// thick, averaged over the next `average_s` seconds (half a second unless given), against
// rho0 g (H - z); and the spurious velocity at the end. The same errors of each half second of the
// average alone (windows) tell a column at rest, whose profile holds from window to window, from one
// still moving.
struct HydrostaticResult {
    double height = 0.0, spacing = 0.0, reference_scale = 0.0;   // H (the lattice's depth, whole layers), dx, rho0 g H
    std::size_t particles = 0;
    // A layer one spacing thick: its mean pressure, the reference at its centre, its particles a frame,
    // and their rms speed and its vertical part over the average (where the column's motion lives).
    struct Layer { double z, pressure, reference; int particles; double rms_speed, rms_vertical; };
    std::vector<Layer> layers;
    double max_error = 0.0;   // max |p - p_ref| / (rho0 g H) in the interior: a kernel support from floor and surface
    // The same over pairs of neighbouring layers pooled (both ways of pairing), two spacings thick: a
    // pressure alternating layer to layer (a mode that puts no net force on a lattice particle) cancels
    // there. Each pair's error is a weighted mean of its layers', so it is at most max_error.
    double pair_error = 0.0;
    double floor_error = 0.0;   // |p - p_ref| / (rho0 g H) of the layer on the floor
    // The floor layer and the one above it pooled, against the reference at their particles' mean height:
    // the layer-to-layer alternation's phase, which puts the floor's excess in one layer or the other from
    // run to run, cancelled (docs/VALIDATION.md "The floor layer's two states, and the tank's 4 ms step").
    double floor_pair_error = 0.0;
    // The same as max_error over the particles more than a kernel support from the side walls too (the
    // layers' core), and the floor layer's core: what the walls' boundary term does not reach.
    double core_error = 0.0, core_floor_error = 0.0;
    double max_speed = 0.0, rms_speed = 0.0;            // at the end of the run (m/s)
    double mean_rms_speed = 0.0;                        // the rms speed averaged over the average's frames
    double average_seconds = 0.0;                       // the simulated time averaged over
    // Each half second of the average on its own (the last may be shorter): its start (s after the
    // settling) and its max_error and floor_error.
    struct Window { double start, max_error, floor_error; };
    std::vector<Window> windows;
    std::uint64_t steps = 0;                            // the solver's steps over the run
    double seconds = 0.0;                               // the run on the wall clock
    RunStats stats;
    // The relaxation before the run (none: relax_frames = 0): its frames and solver steps up to the one
    // that met the bound (all it ran when none did), each frame's rms speed before its velocities were
    // set to zero (the last is the start's residual), that frame's largest speed, whether the bound was
    // reached, and its wall time (all it ran). The run's steps, seconds and stats above do not include it.
    int relax_frames = 0;
    std::uint64_t relax_steps = 0;
    std::vector<double> relax_rms_speeds;
    double relax_max_speed = 0.0;
    bool relaxed = false;
    double relax_seconds = 0.0;
};
// Without a Relaxation: the lattice start (the sweep's rows, docs/SWEEP.md).
HydrostaticResult hydrostatic(const scene::Scene& scene, const shader::FileSource& shaders, double settle_s,
                              frame::Progress* progress = nullptr);
HydrostaticResult hydrostatic(const scene::Scene& scene, const shader::FileSource& shaders, double settle_s,
                              const Relaxation& relaxation, frame::Progress* progress = nullptr, double average_s = 0.5);

// A standing wave (docs/VALIDATION.md "Standing wave"): water of depth H in a tank of length L, its
// surface raised to H + A cos(k x), k = pi/L, released at rest. Linear theory: the first mode's period
// T = 2 pi / sqrt(g k tanh(k H)), and viscosity damps its amplitude as exp(-2 nu k^2 t) in the bulk
// (the walls' boundary layers add more). The mode's amplitude is read as the fluid's first cosine
// moment m(t) = (1/N) sum_i y_i cos(k x_i) of every frame's positions, read back asynchronously
// (ParticleSnapshots); its period from the times m crosses its mean, its decay from the ratio of its swings.
// `scene()` builds the case's scene (tank 0.4 x 0.3 x 0.04 m, H = 0.1 m, A = 0.01 m, spacing 0.01 m).
struct StandingWaveResult {
    double length = 0.0, depth = 0.0, amplitude = 0.0, wavenumber = 0.0, spacing = 0.0;
    std::size_t particles = 0;
    std::vector<std::pair<double, double>> moment;   // (t, m(t)) a frame
    double period_theory = 0.0, period = 0.0, period_error = 0.0;   // s, s, |T - T_theory| / T_theory
    double decay_rate = 0.0, decay_theory = 0.0;     // 1/s: measured, and the bulk's 2 nu k^2
    int half_periods = 0;                            // mean crossings the period was measured over
    std::uint64_t steps = 0;
    double seconds = 0.0;
    RunStats stats;
};
scene::Scene standing_wave_scene();

// A case that ran (no guard fired) but whose flow does not give its measurement: the standing wave's
// surface that does not oscillate. The sweep records the row as "no result" and goes on.
class NoMeasurement : public Error {
public:
    explicit NoMeasurement(const std::string& what) : Error(what) {}
};

// A case's own scene: the bundled one of its name, standing_wave_scene(), or for a scene case
// "scene:NAME" the bundled SPH scene NAME. InputError for another name, or a scene:NAME that is not
// a bundled SPH scene.
scene::Scene case_scene(const std::string& name);
StandingWaveResult standing_wave(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress = nullptr);
// The mode's period and decay from r.moment and r.period_theory (standing_wave's last step): the
// period from the mean crossings after the first quarter period (linear between samples), the decay
// from the largest swings of the first and last half periods. NoMeasurement with fewer than two
// crossings.
void measure_mode(StandingWaveResult& r);

// The pressure on a wall or a box the surge strikes, against an experiment's sensors (docs/VALIDATION.md
// "Impact pressure"): p/(rho0 g H) against T = t sqrt(g/H), H the column's height. Two cases:
//   impact-pressure   Lobovsky et al. (2014), "Experimental investigation of dynamic pressure loads
//                     during dam break", H = 0.3 m: a column 0.6 m long collapses along a tank 1.61 m long
//                     and 0.15 m wide onto its far wall, where sensors at 3, 30 and 80 mm above the floor
//                     (their P1, P3, P4) recorded it (media/validation/lobovsky_exp_data_p{1,3,4}.csv);
//                     the run-up compared over T in [3, 5.5], before the second impact near T = 6 (the
//                     wave that overturns back onto the wall). Its scene: spacing 0.0125 m, H/dx = 24,
//                     13,824 particles.
//   obstacle-impact   Kleefsman et al. (2005), SPHERIC's test 2, H = 0.55 m: a column 1.228 m long across
//                     the whole 1 m width of a 3.22 m tank collapses onto a box 0.161 m high and 0.403 m
//                     wide, whose face towards it held sensors at 21 and 101 mm above the floor (their P1,
//                     P3: media/validation/kleefsman_exp_data_p{1,3}.csv); compared over T in [2.5, 7],
//                     the flow piled against the box after its impact. Its scene: spacing 0.034375 m, H/dx =
//                     16, 16,240 particles.
// H is the depth of the lattice that fills the column. The simulated sensor reads the frame's pressure
// of the fluid beside it (probe_pressure()), every frame's state read back asynchronously
// (ParticleSnapshots), each sample at the time its pressure is of (sample_offset). Compared
// (compare_sensor()): the impact's time, the largest reading, and the readings over the case's window.
// The sensors' heights scale with the column's block, the probe's place with the spacing.
struct ImpactPressureResult {
    std::string source;                              // the experiment, as a citation
    double height = 0.0, spacing = 0.0, face = 0.0;  // H (the column's lattice), dx, x of the face struck
    double window[2] = {0.0, 0.0};                   // T: the readings compared after the impact
    // Frames before a frame's end its sample's time stands: the solver's pressure_sample_offset()
    // (sim/solver.h): 0.5 for DFSPH, whose Density.y is the frame's Δt-weighted mean, 0 for WCSPH and PBF.
    double sample_offset = 0.0;
    std::size_t particles = 0;
    struct Sensor {
        std::string name;   // the experiment's: P1, P3, ...
        double z = 0.0;     // height above the floor (m)
        std::vector<std::pair<double, double>> measured, simulated;   // (T, p/(rho0 g H))
        // The first T at which the reading reaches kImpactOnset (linear between samples); none if never.
        std::optional<double> onset_measured, onset_simulated;
        double peak_measured = 0.0, peak_simulated = 0.0;   // the largest readings
        // Over the window: the time-weighted mean of each series at the experiment's times there (the
        // simulation's interpolated to them; trapezoid weights), and the rms of their differences;
        // `compared` such times.
        double mean_measured = 0.0, mean_simulated = 0.0, rms_error = 0.0;
        int compared = 0;
    };
    std::vector<Sensor> sensors;
    std::uint64_t steps = 0;
    double seconds = 0.0;
    RunStats stats;
};
constexpr double kImpactOnset = 0.25;   // p/(rho0 g H) that marks a sensor's impact
// The cases `ranryu validate` runs, for its messages and help.
constexpr const char* kCaseList = "dam-break, hydrostatic, standing-wave, impact-pressure, obstacle-impact";
scene::Scene impact_pressure_scene();
scene::Scene obstacle_impact_scene();
// InputError, naming the case, where `scene` is not one the case `case_name` can read: not SPH with one
// block, its column not where the case needs it (impact-pressure: against the tank's wall at its smallest
// x, no obstacle; obstacle-impact: a box obstacle, the first, and the column beyond its face at larger x),
// or its spacing leaves the column fewer than two layers. Other cases: nothing checked here.
void check_case_scene(const std::string& case_name, const scene::Scene& scene);
// Run to T = `until` (the experiment's last sample when 0). InputError as check_case_scene(), or where
// `until` leaves the window out.
ImpactPressureResult impact_pressure(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress = nullptr,
                                     double until = 0.0);
// Whether `case_name` names one of the two impact cases, and that case's run (impact_pressure() or
// obstacle_impact()), for the commands that take a case by name.
bool is_impact_case(const std::string& case_name);
ImpactPressureResult impact_case(const std::string& case_name, const scene::Scene& scene, const shader::FileSource& shaders,
                                 frame::Progress* progress = nullptr);
ImpactPressureResult obstacle_impact(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress = nullptr,
                                     double until = 0.0);

// A wall sensor's reading from a frame's particles: the pressures (Density.y) of the particles whose
// distance from the point (x, y) in the x-y plane is under `radius` and whose z lies in [z_lo, z_hi]
// (the sensor's strip across the face) and which lie on the fluid's side of the face x = `face`
// (side·(x − face) > 0; side 0: no face), averaged with the weights (1 − r²/radius²)³ (Shepard's
// normalisation: a constant pressure reads exactly); 0 where no particle is that near (dry: the
// gauge's zero, the atmosphere's pressure).
struct Probe {
    double x = 0.0, y = 0.0, z_lo = 0.0, z_hi = 0.0, radius = 0.0;
    double face = 0.0, side = 0.0;
};
double probe_pressure(const Probe& probe, std::span<const glm::vec4> positions, std::span<const glm::vec4> densities);
// A sensor's comparisons from its two series over T in [window_from, window_to] (the cases' last step;
// the fields above). NoMeasurement where the simulation covers none of the experiment's times there.
void compare_sensor(ImpactPressureResult::Sensor& s, double window_from, double window_to);

// Scene cases (docs/SWEEP.md "Scene cases"): "scene:NAME" runs the bundled SPH scene NAME as it is.
constexpr const char* kScenePrefix = "scene:";
bool is_scene_case(const std::string& case_name);
// Every bundled SPH scene as a scene case ("scene:dam-break", ...), in `ranryu scenes` order.
std::vector<std::string> scene_cases();

// The mean compression of `count` particles, (1/count)·Σ_i max(rho_i/rho0 - 1, 0), computed on the GPU
// (glsl/validation/mean_compression.comp: two dispatches, no atomics) and read back asynchronously
// (gl::AsyncReadback, 16 bytes a measurement): nothing in measure() waits or allocates unless the
// readback ring is a whole `kDepth` measurements behind (its back-pressure). Values reach `on_value`,
// oldest first and each with the tag it was measured under, from poll(), drain() or a later measure().
// Within 1e-5 (relative) of the same mean summed on the CPU in double from the read-back densities
// (tests/gl/compression_test.cpp). Programs and buffers are made here, at start-up.
class CompressionMeter {
public:
    using Consumer = std::function<void(std::uint64_t tag, double mean)>;
    static constexpr int kDepth = 4;
    // Timed as the pass "mean-compression" (its two dispatches "mean-compression.partials" and
    // "mean-compression.total" within it); measure() runs inside `timer`'s frames.
    CompressionMeter(const shader::FileSource& shaders, profile::GpuTimer& timer, std::size_t count, float rest_density, Consumer on_value);
    CompressionMeter(const CompressionMeter&) = delete;   // the readback's consumer holds `this`
    CompressionMeter& operator=(const CompressionMeter&) = delete;

    // Queues the measurement of `densities` (vec4 a particle, rho in x, `count` of them) as they will be
    // once the GPU has run what was queued before, tagged `tag` (a frame number).
    void measure(const gl::Buffer& densities, std::uint64_t tag);
    std::size_t poll();    // hands over the measurements that have arrived; never waits
    std::size_t drain();   // waits for every queued one: end of a run and tests only

private:
    profile::GpuTimer& timer_;
    profile::PassId pass_, partials_pass_, total_pass_;
    std::size_t count_;
    std::uint32_t groups_;   // workgroups of the first pass (at most 1024)
    Consumer on_value_;
    shader::Program partials_, total_;
    gl::Buffer partial_sums_, total_sum_;
    gl::AsyncReadback readback_;
};

// A scene run as it is for `seconds` of simulated time (whole frames, at least one), with no
// reference to compare with: whether it holds together (the guard, as in every case) and how far it
// compresses. The compression, mean over particles of max(rho/rho0 - 1, 0), is measured after every
// frame on the GPU and comes back asynchronously, frames late (CompressionMeter; nothing in the frame
// loop waits for it): its largest value and when, and its average over the frames. With PBF the
// densities are those of each step's last iteration, as the guard reads them.
struct SceneRunResult {
    std::size_t particles = 0;
    int frames = 0;
    double peak_mean_compression = 0.0;      // max over frames of the mean compression
    double peak_time = 0.0;                  // the simulated time of that frame (s)
    double average_mean_compression = 0.0;   // the mean compression averaged over the frames
    // Whether a gain of energy means an instability: true for a closed system under gravity (it only
    // loses energy); false where a force does work on the fluid (the turbulence force, amplitude > 0).
    bool energy_conserving = true;
    std::uint64_t steps = 0;
    double seconds = 0.0;                    // the run on the wall clock
    RunStats stats;
};
SceneRunResult scene_run(const scene::Scene& scene, const shader::FileSource& shaders, double seconds,
                         frame::Progress* progress = nullptr);

}  // namespace ranryu::validation
