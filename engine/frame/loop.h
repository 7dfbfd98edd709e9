#pragma once
// The frame loop every command runs (run, record, profile, validate): the frame as its list of
// passes, with the command's own work at fixed points.
//
//     hooks.before(pipeline)        input, camera (run)
//     pipeline.begin_frame()
//     pipeline.simulate()           unless hooks.advance says hold (run's pause)
//     pipeline.draw()               when the view draws
//     hooks.after_draw(pipeline)    capture (record), present (run)
//     pipeline.end_frame()
//     pipeline.poll()               the records that came back (never waits)
//     hooks.after(pipeline)         what the command does with them
//
// The loop ends after `frames` frames (none: until hooks.keep_going says stop), at the first frame
// whose record shows an instability, or at the frame boundary after SIGINT or SIGTERM once the
// command has called stop_on_signals() (frame/stop.h): the caller decides what to report (the loop
// never throws it). A command's progress line is a Progress's update() in hooks.after
// (frame/progress.h).
#include <cstdint>
#include <functional>
#include <optional>

#include "frame/pipeline.h"

namespace ranryu::frame {

struct FrameHooks {
    std::function<void(Pipeline&)> before;
    std::function<void(Pipeline&)> after_draw;
    std::function<void(Pipeline&)> after;
    std::function<bool(const Pipeline&)> keep_going;   // asked before each frame
    // Asked before simulate(): false holds the simulation for this frame (it is still drawn from the
    // state that the last simulated frame left). None: every frame simulates.
    std::function<bool(const Pipeline&)> advance;
};

// Runs frames; returns how many it ran.
std::uint64_t run_frames(Pipeline& pipeline, std::optional<std::uint64_t> frames, const FrameHooks& hooks = {});

}  // namespace ranryu::frame
