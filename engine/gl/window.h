#pragma once
// A GLFW window with an OpenGL 4.3 core context (only in builds configured with GLFW). It gathers the
// input that the app turns into commands (input/commands.h): the left- and right-button drags and the wheel, and
// the presses of the keys the app answers, by name.
#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include <glm/glm.hpp>

#include "gl/context.h"

struct GLFWwindow;

namespace ranryu::gl {

class Window {
public:
    Window(int width, int height, const std::string& title, bool debug);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    const DeviceInfo& info() const { return info_; }
    bool should_close() const;
    void poll();
    void swap();
    glm::ivec2 framebuffer_size() const;

    // Input since the last call: drags in pixels (left button, right button), wheel in notches.
    struct Input {
        glm::vec2 drag{0.0f};
        glm::vec2 right_drag{0.0f};
        float wheel = 0.0f;
    };
    Input take_input();
    // The keys pressed since the last call, by input::keys() name ("space", "n", ..., "f12",
    // "escape", "1".."9"), in order; at most kMaxKeys a frame (more are dropped). No allocation.
    static constexpr std::size_t kMaxKeys = 16;
    struct Keys {
        std::array<std::string_view, kMaxKeys> names;
        std::size_t count = 0;
    };
    Keys take_keys() { return std::exchange(keys_, Keys{}); }

    GLFWwindow* handle() const { return window_; }   // for the overlay's GLFW backend

private:
    GLFWwindow* window_ = nullptr;
    DeviceInfo info_;
    Input input_;
    Keys keys_;
    glm::dvec2 last_cursor_{0.0};
    bool dragging_ = false, right_dragging_ = false;
};

}  // namespace ranryu::gl
