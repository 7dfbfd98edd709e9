#include "input/commands.h"

#include <array>

namespace ranryu::input {

namespace {
constexpr std::array<Key, 12> kKeys{{
    {"space", "pause / resume the simulation (the picture is still drawn)"},
    {"n", "single step: one frame of simulation while paused"},
    {"r", "reset: restart the scene from its first frame"},
    {"m", "next shading mode: water, fresnel, phong, gouraud, particles (restarts the scene)"},
    {"t", "turbulence force on / off (live where the scene has it, else a restart)"},
    {"1-9", "the bundled scene of that number, in `ranryu scenes` order (restarts)"},
    {"p", "paddle on / off: a sphere to drag through the liquid with the right mouse button (SPH scenes)"},
    {"e", "emitter on / off: pour liquid in, up to the particle budget (SPH scenes)"},
    {"h", "hide / show the panel"},
    {"f12", "screenshot into the --shots folder (never overwrites)"},
    {"f9", "record on / off: the window's frames into the --record-dir folder (never overwrites)"},
    {"escape", "quit"},
}};
}  // namespace

std::span<const Key> keys() { return kKeys; }

std::optional<Command> key_command(std::string_view name) {
    Command c;
    if (name == "space") c.kind = Kind::toggle_pause;
    else if (name == "n") c.kind = Kind::step;
    else if (name == "r") c.kind = Kind::reset;
    else if (name == "m") c.kind = Kind::next_shading;
    else if (name == "t") c.kind = Kind::toggle_turbulence;
    else if (name == "h") c.kind = Kind::toggle_panel;
    else if (name == "p") c.kind = Kind::toggle_paddle;
    else if (name == "e") c.kind = Kind::toggle_emitter;
    else if (name == "f9") c.kind = Kind::toggle_record;
    else if (name == "f12") c.kind = Kind::screenshot;
    else if (name == "escape") c.kind = Kind::quit;
    else if (name.size() == 1 && name[0] >= '1' && name[0] <= '9') {
        c.kind = Kind::scene;
        c.index = name[0] - '1';
        if (std::size_t(c.index) >= scene::bundled().size()) return std::nullopt;
    } else {
        return std::nullopt;
    }
    return c;
}

std::string keys_help() {
    std::string text;
    for (const Key& k : kKeys) {
        std::string name(k.name);
        if (name == "f12") name = "F12";
        else if (name == "f9") name = "F9";
        else if (name == "escape") name = "Esc";
        text += "  " + name + std::string(name.size() < 8 ? 8 - name.size() : 1, ' ') + std::string(k.help) + "\n";
    }
    return text;
}

}  // namespace ranryu::input
