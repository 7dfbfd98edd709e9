#pragma once
// A run's state on disk, to go on from where it stopped: `record` and `profile` write one with
// --checkpoint FILE when they end (done, or stopped by SIGINT or SIGTERM: a batch system's time
// limit) and start from one with --resume FILE. The resumed run is the run that wrote it, continued:
// the same scene (rebuilt from the JSON text the file holds, at its spacing and with its solver),
// frame numbers that go on from its last frame, and every buffer and value the simulation carries from
// frame to frame (frame::Pipeline::persist, sim/state_io.h): it goes on from exactly the state the
// stopped run had, and its frames are an unstopped run's: WCSPH and DFSPH plan each frame's substeps
// (and DFSPH its iteration caps) from the record of the frame sim::Fluid::plan_lag() frames back, never
// from whatever newer one a stopped run drained, and the checkpoint carries those records
// (tests/gl/checkpoint_test.cpp compares the run that wrote a checkpoint, one loaded from it and one
// never stopped, bit for bit; tests/cli/checkpoint_test.cpp a record's frames, byte for byte).
//
// The file: the 8 bytes "RANRYUCP", a u32 format version (1), a u64 length and a JSON header of that
// length, then each entry's bytes in the header's order (numbers in the machine's byte order: a
// checkpoint is for the build, and so the machine, that wrote it):
//
//     {"format": 1, "build": "0.1.0 58d1dd5", "frame": 300, "time": 5.0, "particles": 1000000,
//      "scene": {"source": "<the scene's JSON text>", "origin": "bundled", "name": "dam-break",
//                "spacing": 0.002, "solver": "wcsph"},
//      "entries": [{"name": "pipeline.frames", "bytes": 8}, {"name": "fluid.positions", "bytes": 16000000}, ...]}
//
// It is written whole or not at all (core/whole_file.h: FILE.tmp, synced to disk, renamed over FILE),
// so a failed write, or a machine that goes down at the end of a batch job, loses no earlier FILE.
#include <cstdint>
#include <filesystem>
#include <string>

#include "frame/pipeline.h"
#include "scene/scene.h"

namespace ranryu::frame {

struct CheckpointInfo {
    scene::Scene scene;          // as the run that wrote it had it (spacing and solver applied)
    std::uint64_t frame = 0;     // the next frame to run
    double time = 0.0;           // simulated seconds at the end of the last frame
    std::size_t particles = 0;
};

// Writes `pipeline`'s state to `file`, with `build` naming the build (the app's version and commit:
// read_checkpoint() refuses another's). Call at the end of a run: it drains the pipeline's records and
// reads every buffer back (it waits for the GPU). Throws InputError, naming `what` ("--checkpoint FILE"),
// and writes nothing when the run's last frame is not known sound (an instability, or a frame past a
// guard bound that the next frame has not yet shown to be a spike) or the file cannot be written.
void write_checkpoint(Pipeline& pipeline, const std::filesystem::path& file, const std::string& what, const std::string& build);

// Before a run: that `file` can be written (FILE.tmp is made and removed), so a bad path is
// refused before any work. Throws InputError naming `what`.
void check_checkpoint_path(const std::filesystem::path& file, const std::string& what);

// The header of `file`: the scene to build the pipeline from, and where the run stopped. Throws
// InputError naming `what` ("--resume FILE") on a missing, unreadable, truncated or foreign file, or
// one that another `build` wrote.
CheckpointInfo read_checkpoint(const std::filesystem::path& file, const std::string& what, const std::string& build);

// Loads `file`'s state into `pipeline`, built from read_checkpoint(file).scene and not yet run.
// Throws InputError naming `what` when an entry is missing or of another size (a file written by
// another build, or another view of the scene).
void load_checkpoint(Pipeline& pipeline, const std::filesystem::path& file, const std::string& what);

}  // namespace ranryu::frame
