#pragma once
// A GLFW window with an OpenGL 4.3 core context (only in builds configured with GLFW). Mouse drag
// orbits the camera around its target, the wheel zooms, Escape closes.
#include <memory>
#include <string>

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

    // Input since the last call: drag in pixels, wheel in notches.
    struct Input {
        glm::vec2 drag{0.0f};
        float wheel = 0.0f;
    };
    Input take_input();

    GLFWwindow* handle() const { return window_; }   // for the overlay's GLFW backend

private:
    GLFWwindow* window_ = nullptr;
    DeviceInfo info_;
    Input input_;
    glm::dvec2 last_cursor_{0.0};
    bool dragging_ = false;
};

}  // namespace ranryu::gl
