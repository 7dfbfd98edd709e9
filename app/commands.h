#pragma once
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "cli.h"
#include "frame/progress.h"
#include "gl/context.h"
#include "profile/report.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "shader/source.h"

namespace ranryu::app {
// Each returns the process exit code or throws ranryu::Error (see core/error.h).
int run(const Options& o);
int record(const Options& o);
int profile_cmd(const Options& o);
int scenes(const Options& o);
int validate(const Options& o);
int sweep(const Options& o);
int export_field(const Options& o);

// Shared by the commands: the shader files (embedded, or --shader-dir), a headless context that
// prints the device line, and the scene at --spacing with --solver.
shader::FileSource shader_source(const Options& o);
// `announce` = false leaves the device line to print_device(), for a command that checks more first.
std::unique_ptr<gl::HeadlessContext> headless(const Options& o, bool announce = true);
scene::Scene load_scene(const Options& o);
scene::Scene with_options(scene::Scene s, const Options& o);   // --spacing, --solver
// The progress line on stderr (frame/progress.h) labelled `label`: none with --quiet; on a log, a
// line every 10 s or every RANRYU_PROGRESS_SECONDS (InputError when that is not a number of seconds).
frame::Progress make_progress(const Options& o, const std::string& label);
// A debug context (always in Debug builds; --gl-debug in others); --shading; --size or the scene's;
// the device line on stdout; the run's facts for a report.
bool debug_context(const Options& o);
std::optional<render::Shading> shading(const Options& o);
glm::ivec2 image_size(const Options& o, const scene::Scene& s);
void print_device(const gl::DeviceInfo& d);
// --records, --json, --csv and --checkpoint, where given: each checked writable (profile::check_writable)
// before any work, so that a run is not spent, nor an earlier one removed, for a file that cannot be written.
void check_report_files(const Options& o);
profile::RunInfo run_info(const gl::DeviceInfo& d, const frame::Pipeline& p, int frames, int warmup);
}  // namespace ranryu::app
