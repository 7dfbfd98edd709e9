#include "input/script.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace ranryu::input {

namespace {

struct LineError {
    std::string what;
};

bool on_off(const std::vector<std::string>& w, std::size_t i) {
    if (w.size() != i + 1 || (w[i] != "on" && w[i] != "off")) throw LineError{"panel " + w[i - 1] + ": expected on or off"};
    return w[i] == "on";
}

float number(const std::string& text, const std::string& what) {
    char* end = nullptr;
    const float v = std::strtof(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v) || std::fabs(v) > 1e5f)
        throw LineError{what + " \"" + text + "\": expected a number in [-100000, 100000]"};
    return v;
}

void arity(const std::vector<std::string>& w, std::size_t n, const std::string& form) {
    if (w.size() != n) throw LineError{"expected \"FRAME " + form + "\""};
}

Command panel(const std::vector<std::string>& w) {
    if (w.size() < 3) throw LineError{"panel: name an action (pause, step, reset, screenshot, quit, panel, shading, scene, solver, turbulence, "
                        "amplitude, viscosity, cfl, paddle, emitter, record, spacing)"};
    const std::string& a = w[2];
    Command c;
    if (a == "pause") c.kind = Kind::set_pause, c.on = on_off(w, 3);
    else if (a == "panel") c.kind = Kind::set_panel, c.on = on_off(w, 3);
    else if (a == "step" || a == "reset" || a == "screenshot" || a == "quit") {
        arity(w, 3, "panel " + a);
        c.kind = a == "step" ? Kind::step : a == "reset" ? Kind::reset : a == "screenshot" ? Kind::screenshot : Kind::quit;
    } else if (a == "shading") {
        arity(w, 4, "panel shading MODE");
        const auto s = render::parse_shading(w[3]);
        if (!s) throw LineError{"panel shading " + w[3] + ": expected one of water, fresnel, phong, gouraud, particles"};
        c.kind = Kind::shading, c.shading = *s;
    } else if (a == "scene") {
        arity(w, 4, "panel scene NAME");
        const std::vector<scene::BundledScene> all = scene::bundled();
        std::string names;
        c.kind = Kind::scene, c.index = -1;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (all[i].name == w[3]) c.index = int(i);
            names += (i ? ", " : "") + all[i].name;
        }
        if (c.index < 0) throw LineError{"panel scene " + w[3] + ": no bundled scene of that name (" + names + ")"};
    } else if (a == "turbulence") {
        c.kind = Kind::turbulence, c.on = on_off(w, 3);
    } else if (a == "paddle") {
        c.kind = Kind::set_paddle, c.on = on_off(w, 3);
    } else if (a == "emitter") {
        c.kind = Kind::set_emitter, c.on = on_off(w, 3);
    } else if (a == "record") {
        c.kind = Kind::set_record, c.on = on_off(w, 3);
    } else if (a == "spacing") {
        arity(w, 4, "panel spacing DX");
        c.kind = Kind::spacing;
        c.x = number(w[3], "panel spacing");
        // scene::with_spacing checks the particle count; the spacing itself must be a length.
        if (!(c.x >= 1e-4f && c.x <= 1.0f)) throw LineError{"panel spacing " + w[3] + ": expected metres in [0.0001, 1]"};
    } else if (a == "viscosity" || a == "cfl" || a == "amplitude") {
        arity(w, 4, "panel " + a + " VALUE");
        c.kind = a == "viscosity" ? Kind::viscosity : a == "cfl" ? Kind::cfl : Kind::amplitude;
        c.x = number(w[3], "panel " + a);
        // The scene file's ranges (scene/scene.cpp); A > 0: 0 is "turbulence off".
        const bool ok = a == "viscosity" ? c.x >= 0.0f && c.x <= 10.0f : a == "cfl" ? c.x >= 0.01f && c.x <= 1.0f : c.x > 0.0f && c.x <= 1e4f;
        if (!ok)
            throw LineError{"panel " + a + " " + w[3] + ": expected " +
                            (a == "viscosity" ? "m^2/s in [0, 10]" : a == "cfl" ? "a Courant number in [0.01, 1]" : "1/m in (0, 10000]")};
    } else if (a == "solver") {
        arity(w, 4, "panel solver NAME");
        if (w[3] != "dfsph" && w[3] != "wcsph" && w[3] != "pbf") throw LineError{"panel solver " + w[3] + ": expected dfsph, wcsph or pbf"};
        c.kind = Kind::solver, c.solver = scene::parse_solver(w[3], "panel solver");
    } else {
        throw LineError{"panel " + a + ": no such action (pause, step, reset, screenshot, quit, panel, shading, scene, solver, "
                        "turbulence, amplitude, viscosity, cfl, paddle, emitter, record, spacing)"};
    }
    return c;
}

Event parse_line(const std::vector<std::string>& w, int line) {
    Event e;
    e.line = line;
    const std::string& f = w[0];
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), e.frame);
    if (ec != std::errc() || end != f.data() + f.size() || e.frame > 100'000'000)
        throw LineError{"\"" + f + "\": expected a frame number (a whole number from 0) first"};
    if (w.size() < 2) throw LineError{"frame " + f + " has no event (key, drag, paddle, wheel, panel)"};
    const std::string& ev = w[1];
    if (ev == "key") {
        arity(w, 3, "key NAME");
        const auto c = key_command(w[2]);
        if (!c) {
            std::string names;
            for (const Key& k : keys()) names += (names.empty() ? "" : " ") + std::string(k.name);
            throw LineError{"key " + w[2] + ": no such key (keys: " + names + "; 1-9 up to the number of bundled scenes)"};
        }
        e.command = *c;
    } else if (ev == "drag") {
        arity(w, 4, "drag DX DY");
        e.command.kind = Kind::drag;
        e.command.x = number(w[2], "drag DX");
        e.command.y = number(w[3], "drag DY");
    } else if (ev == "paddle") {
        arity(w, 4, "paddle DX DY");
        e.command.kind = Kind::paddle_drag;
        e.command.x = number(w[2], "paddle DX");
        e.command.y = number(w[3], "paddle DY");
    } else if (ev == "wheel") {
        arity(w, 3, "wheel N");
        e.command.kind = Kind::wheel;
        e.command.x = number(w[2], "wheel N");
    } else if (ev == "panel") {
        e.command = panel(w);
    } else {
        throw LineError{"\"" + ev + "\": no such event (key, drag, paddle, wheel, panel)"};
    }
    return e;
}

}  // namespace

std::vector<Event> parse_script(const std::string& text, const std::string& name) {
    std::vector<Event> events;
    std::istringstream in(text);
    int line = 0;
    for (std::string s; std::getline(in, s);) {
        ++line;
        if (const auto hash = s.find('#'); hash != std::string::npos) s.resize(hash);
        std::vector<std::string> words;
        std::istringstream ws(s);
        for (std::string w; ws >> w;) words.push_back(w);
        if (words.empty()) continue;
        try {
            Event e = parse_line(words, line);
            if (!events.empty() && e.frame < events.back().frame)
                throw LineError{"frame " + std::to_string(e.frame) + " comes after frame " + std::to_string(events.back().frame) +
                                " (frames must not decrease)"};
            events.push_back(e);
        } catch (const LineError& err) {
            throw InputError("--script " + name + ":" + std::to_string(line) + ": " + err.what);
        }
    }
    return events;
}

std::vector<Event> load_script(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in || std::filesystem::is_directory(file)) throw InputError("--script " + file.string() + ": cannot read the file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse_script(ss.str(), file.string());
}

}  // namespace ranryu::input
