#pragma once
// `ranryu run --script FILE`: timed input for the window, replayed through the same Commands a person
// makes (input/commands.h), so the window can be tested under Xvfb. One event a line:
//
//     # a comment; blank lines are skipped
//     FRAME key NAME            a key: space n r m t p e h f12 f9 escape 1-9
//     FRAME drag DX DY          a mouse drag of (DX, DY) pixels on the picture (orbits the camera)
//     FRAME paddle DX DY        a right-button drag of (DX, DY) pixels (moves the paddle)
//     FRAME wheel N             N notches of the mouse wheel (zoom)
//     FRAME panel ACTION [ARG]  a widget of the panel: pause on|off, step, reset, screenshot, quit,
//                               panel on|off, shading MODE, scene NAME, solver dfsph|wcsph|pbf,
//                               turbulence on|off, amplitude A, viscosity NU, cfl C, paddle on|off,
//                               emitter on|off, record on|off, spacing DX
//
// FRAME is the number of the frame (from 0, counted over the whole run, restarts included) before
// which the event acts: `0 key h` hides the panel before the first frame is drawn, `5 key f12` saves
// the sixth frame drawn. Frames never decrease from one line to the next. The script does not end the
// run: end it with `quit` (or --frames).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "input/commands.h"

namespace ranryu::input {

struct Event {
    std::uint64_t frame = 0;
    Command command;
    int line = 0;   // in the script, from 1
};

// Parses a script's text; `name` is what errors call it. Throws InputError "NAME:LINE: what is wrong".
std::vector<Event> parse_script(const std::string& text, const std::string& name);
// Reads and parses FILE; an unreadable file is an InputError naming it.
std::vector<Event> load_script(const std::filesystem::path& file);

// The events of a script in order; take() hands out those due before a frame.
class Replay {
public:
    Replay() = default;
    explicit Replay(std::vector<Event> events) : events_(std::move(events)) {}
    // The next event due at or before `frame`, or null (and the cursor stays).
    const Event* next_due(std::uint64_t frame) const {
        return next_ < events_.size() && events_[next_].frame <= frame ? &events_[next_] : nullptr;
    }
    void pop() { ++next_; }
    bool done() const { return next_ >= events_.size(); }

private:
    std::vector<Event> events_;
    std::size_t next_ = 0;
};

}  // namespace ranryu::input
