#pragma once
// SIGINT and SIGTERM as a request to stop a run at the next frame boundary. The handler sets a
// flag (a std::sig_atomic_t); run_frames() (frame/loop.h) reads it before each frame and ends the
// loop, and the command finishes what it started (record writes every frame it captured and
// run.json) and exits 130 through interrupted(). A second signal a second or more after the first ends
// the process the default way, for a run that will not come to a frame boundary; one within the
// second is the same request delivered twice (timeout(1) signals the command, then its process group)
// and is ignored.
#include <cstdint>
#include <optional>

#include "core/error.h"

namespace ranryu::frame {

// Installs the handlers (the commands that run frames). Until then the defaults stand.
void stop_on_signals();
// The signal that asked the run to stop, if one did.
std::optional<int> stop_signal();
inline bool stop_requested() { return stop_signal().has_value(); }

// The error a run stopped by a signal ends with (exit code 130): "interrupted by SIGINT after 37 of
// 120 frames" (`total` 0: unknown).
Error interrupted(std::uint64_t frames_run, std::uint64_t total = 0);

}  // namespace ranryu::frame
