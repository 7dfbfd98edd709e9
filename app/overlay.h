#pragma once
// The window's overlay (Dear ImGui with its GLFW backend for input, drawn by render::OverlayDraw,
// engine/render/overlay_draw.h, whose GL objects are made once at start-up): a panel with what the CPU already
// knows about the run (fps, GPU ms a frame, the real-time factor, particles and sub-particles,
// substeps and solver iterations a frame, the guard's state, and a bar per pass with its GPU ms from
// the asynchronous timers, frames late), the run's controls, and the keys' help.
//
// Nothing here reads the GPU back or waits for it: the numbers are the timers' results and the
// pipeline's last record, which came back through their rings. The panel is drawn as its own pass,
// "overlay" (a debug group and a GPU timer), after the frame is presented to the window's back buffer.
//
// Headless (`ranryu profile --overlay`, no GLFW needed): with the display size given and a 60 Hz
// clock, the same panel is drawn into the bound framebuffer (the pipeline's
// target), so that its cost per frame can be measured where no window can open.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frame/pipeline.h"
#include "gl/objects.h"
#include "input/commands.h"
#include "profile/gpu_timer.h"
#include "render/overlay_draw.h"
#include "shader/source.h"
#include "sim/guard.h"

struct GLFWwindow;

namespace ranryu::app {

// What the run knows that the pipeline does not: its clocks and its controls' state.
struct OverlayState {
    double fps = 0.0;               // frames a wall second, over the last half second
    std::optional<double> rtf;      // simulated seconds a wall second, over the last half second
    bool paused = false;
    int scene_index = -1;           // in scene::bundled(); -1: a scene from a file
    std::optional<sim::GuardLimits> limits;   // the guard's bounds (SPH)
    // The live settings (SPH): viscosity (m^2/s), the Courant number, the turbulence force and its A.
    float viscosity = 0.0f, cfl = 0.0f, amplitude = 0.0f;
    bool turbulence = false;
    float paddle_radius = 0.0f;     // the paddle's radius (m); 0: the scene has none (ballistic)
    bool paddle = false;            // the paddle is in the liquid
    bool recording = false;         // F9's take is being written
    bool emitter = false;           // the emitter pours
    std::size_t budget = 0;         // the emitter's particle budget; 0: none (ballistic)
    std::string status;             // the last control's note ("scene falling-block: particles only"), or empty
};

// The panel's rectangle in window pixels (top-left origin), as drawn last.
struct PanelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

class Overlay {
public:
    // Start-up: the ImGui context, its GLFW backend, and the panel's program, buffers and font
    // texture (built here, once; a shader of `shaders` that fails throws ranryu::Error).
    Overlay(GLFWwindow* window, const shader::FileSource& shaders);
    // Headless: no input; the panel laid out for a `display` pixels framebuffer.
    Overlay(glm::ivec2 display, const shader::FileSource& shaders);
    ~Overlay();
    Overlay(const Overlay&) = delete;
    Overlay& operator=(const Overlay&) = delete;

    // Whether the panel has the mouse (the drag and the wheel are then the panel's, not the camera's).
    bool wants_mouse() const;
    // Whether a text field of the panel is being typed into (Ctrl+click on a slider): keys are its.
    bool wants_text() const;

    // Builds the panel and draws it into the bound (default) framebuffer as pass `pass` of p's timer.
    // What its widgets ask for is appended to `commands`.
    void draw(frame::Pipeline& p, profile::PassId pass, const OverlayState& state, std::vector<input::Command>& commands);
    // Where the panel was drawn last.
    const PanelRect& panel() const { return panel_; }

private:
    void start(const shader::FileSource& shaders);   // the ImGui context, the panel's GL objects and font texture
    void render();                                   // ImGui's draw data through draw_
    GLFWwindow* window_ = nullptr;
    glm::ivec2 display_{0};
    PanelRect panel_;
    std::vector<std::string> scenes_;   // the bundled scenes' names, for the scene list
    float spacing_ = 0.0f;              // the spacing slider's value while it is dragged
    bool spacing_edit_ = false;
    std::optional<render::OverlayDraw> draw_;
    gl::Texture2D font_;
    std::vector<render::OverlayCommand> commands_;   // a list's, reused from frame to frame
};

}  // namespace ranryu::app
