#include "gl/window.h"

#include <GLFW/glfw3.h>

#include <string_view>
#include <utility>

#include "core/error.h"

namespace ranryu::gl {

Window::Window(int width, int height, const std::string& title, bool debug) {
    glfwSetErrorCallback([](int, const char*) {});
    if (!glfwInit()) {
        const char* why = nullptr;
        glfwGetError(&why);
        throw Error(std::string("cannot open a window: ") + (why ? why : "glfwInit failed") +
                    " (no display? use `ranryu record` or `ranryu profile` headless)");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
    // Robust where the driver offers it, as the headless context (gl/context_egl.cpp): a lost context
    // then reports its reset through glGetGraphicsResetStatus, which gl/faults.h checks at every
    // frame's end, and the run stops with its message instead of drawing garbage. Else a plain one.
    glfwWindowHint(GLFW_CONTEXT_ROBUSTNESS, GLFW_LOSE_CONTEXT_ON_RESET);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwWindowHint(GLFW_CONTEXT_ROBUSTNESS, GLFW_NO_ROBUSTNESS);
        window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    }
    if (!window_) {
        const char* why = nullptr;
        glfwGetError(&why);
        glfwTerminate();
        throw Error(std::string("cannot create an OpenGL 4.3 core window: ") + (why ? why : "unknown reason"));
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(window_, this);
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
        static_cast<Window*>(glfwGetWindowUserPointer(w))->input_.wheel += float(dy);
    });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
        if (action != GLFW_PRESS) return;
        static constexpr std::string_view digits[] = {"1", "2", "3", "4", "5", "6", "7", "8", "9"};
        std::string_view name;
        switch (key) {
            case GLFW_KEY_SPACE: name = "space"; break;
            case GLFW_KEY_N: name = "n"; break;
            case GLFW_KEY_R: name = "r"; break;
            case GLFW_KEY_M: name = "m"; break;
            case GLFW_KEY_T: name = "t"; break;
            case GLFW_KEY_H: name = "h"; break;
            case GLFW_KEY_P: name = "p"; break;
            case GLFW_KEY_E: name = "e"; break;
            case GLFW_KEY_F9: name = "f9"; break;
            case GLFW_KEY_F12: name = "f12"; break;
            case GLFW_KEY_ESCAPE: name = "escape"; break;
            default:
                if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) name = digits[key - GLFW_KEY_1];
                else return;
        }
        Keys& k = static_cast<Window*>(glfwGetWindowUserPointer(w))->keys_;
        if (k.count < kMaxKeys) k.names[k.count++] = name;
    });
    info_ = query_device("GLFW");
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }

void Window::poll() {
    glfwPollEvents();
    glm::dvec2 c;
    glfwGetCursorPos(window_, &c.x, &c.y);
    const bool down = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    if (down && dragging_) input_.drag += glm::vec2(c - last_cursor_);
    dragging_ = down;
    const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (right && right_dragging_) input_.right_drag += glm::vec2(c - last_cursor_);
    right_dragging_ = right;
    last_cursor_ = c;
}

void Window::swap() { glfwSwapBuffers(window_); }

glm::ivec2 Window::framebuffer_size() const {
    glm::ivec2 s;
    glfwGetFramebufferSize(window_, &s.x, &s.y);
    return s;
}

Window::Input Window::take_input() { return std::exchange(input_, Input{}); }

}  // namespace ranryu::gl
