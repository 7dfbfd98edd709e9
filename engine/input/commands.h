#pragma once
// What a person can do to `ranryu run` while it runs, as data: a key, a drag on the picture, or a
// widget of the panel each become one Command, and the window applies every Command the same way
// wherever it came from (app/run.cpp). `run --script FILE` (input/script.h) replays Commands at
// given frames, so the window can be tested without a person.
//
// No GL and no GLFW here: the key names are ours (GLFW's key codes are mapped to them in app/).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "render/renderer.h"
#include "scene/scene.h"

namespace ranryu::input {

enum class Kind : std::uint8_t {
    toggle_pause,   // pause or resume the simulation; the picture is still drawn
    set_pause,      // on: pause, off: resume
    step,           // one frame of simulation while paused
    reset,          // restart the scene (the pipeline is rebuilt)
    toggle_panel,   // hide or show the overlay panel
    set_panel,      // on: show, off: hide
    screenshot,     // the window as it is shown, into the screenshot folder
    quit,
    next_shading,   // cycle water, fresnel, phong, gouraud, particles (restarts the scene)
    shading,        // shading = `shading` (restarts the scene)
    scene,          // bundled scene number `index` (0-based, `ranryu scenes` order; restarts)
    solver,         // solver = `solver` (restarts; SPH scenes only)
    viscosity,      // SPH kinematic viscosity = x (m^2/s), live
    cfl,            // the time step's Courant number = x, live
    turbulence,     // the turbulence force on or off: live where the scene has it, else a restart
    toggle_turbulence,
    amplitude,      // the turbulence force's A = x (1/m): live where the scene has it
    drag,           // orbit the camera as a mouse drag of (x, y) pixels
    wheel,          // zoom as `x` notches of the wheel
    toggle_paddle,  // the paddle (a sphere dragged through the liquid) on or off, live (SPH scenes)
    set_paddle,     // on: the paddle in, off: out
    paddle_drag,    // move the paddle as a right-button drag of (x, y) pixels, in the plane facing the camera
    toggle_emitter, // the emitter pours liquid in (up to the particle budget) or stops, live (SPH scenes)
    set_emitter,    // on: pour, off: stop
    toggle_record,  // recording the window's frames into the --record-dir folder, on or off
    set_record,     // on: record, off: stop
    spacing,        // particle spacing = x (m): the scene rebuilt at that resolution (restarts)
};

struct Command {
    Kind kind = Kind::quit;
    bool on = false;                                   // set_pause, set_panel, turbulence, set_paddle, set_emitter, set_record
    int index = 0;                                     // scene
    render::Shading shading = render::Shading::particles;
    scene::Solver solver = scene::Solver::dfsph;
    float x = 0.0f, y = 0.0f;                          // drag, paddle_drag (pixels), wheel (notches in x), viscosity, cfl, amplitude, spacing
};

// A key of the window: its name (as a script writes it), what it does, and the help line.
struct Key {
    std::string_view name;   // "space", "n", ..., "f12", "escape", "1".."9"
    std::string_view help;
};
// Every key the window answers, in help order (run --help, the panel's help, README).
std::span<const Key> keys();
// The Command of a key by name; nothing for a name that is no key, or a scene key past the bundled
// scenes (1-9 pick the bundled scenes in `ranryu scenes` order).
std::optional<Command> key_command(std::string_view name);
// The keys' help as lines "  NAME   what it does" (run --help and the panel).
std::string keys_help();

}  // namespace ranryu::input
