#include "frame/loop.h"

#include "frame/stop.h"

namespace ranryu::frame {

std::uint64_t run_frames(Pipeline& pipeline, std::optional<std::uint64_t> frames, const FrameHooks& hooks) {
    std::uint64_t ran = 0;
    while ((!frames || ran < *frames) && !pipeline.instability() && !stop_requested() &&
           (!hooks.keep_going || hooks.keep_going(pipeline))) {
        if (hooks.before) hooks.before(pipeline);
        pipeline.begin_frame();
        if (!hooks.advance || hooks.advance(pipeline)) pipeline.simulate();
        pipeline.draw();
        if (hooks.after_draw) hooks.after_draw(pipeline);
        pipeline.end_frame();
        pipeline.poll();
        if (hooks.after) hooks.after(pipeline);
        ++ran;
    }
    return ran;
}

}  // namespace ranryu::frame
