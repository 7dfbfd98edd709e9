#pragma once
// Screenshots of the window without stalling its frames. take() queues a read of the back buffer
// (what the next swap shows, the panel included) into a pixel-pack buffer of a small ring and fences
// it; poll(), once a frame, hands each shot whose copy the GPU has finished to a thread that flips
// its rows, writes the PNG and then prints its line (lines in the order taken); finish(), at the end of a run, waits for the
// rest and rethrows the first write that failed. The render thread waits only when every slot of
// the ring is still in flight (shots asked faster than the GPU runs): back-pressure, not a stall.
#include <cstdint>
#include <filesystem>
#include <future>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/fence_ring.h"
#include "gl/objects.h"

namespace ranryu::app {

class WindowShots {
public:
    explicit WindowShots(int depth = 4) : ring_(std::size_t(depth), "window screenshot") {}
    ~WindowShots();
    WindowShots(const WindowShots&) = delete;
    WindowShots& operator=(const WindowShots&) = delete;

    // Queues the back buffer's fb.x × fb.y pixels for `file`; `line` is printed once it is written.
    void take(std::filesystem::path file, glm::ivec2 fb, std::string line);
    // Hands finished copies to their writers; rethrows a write that failed. Never waits for the GPU.
    void poll();
    // Waits for every copy and write. Idempotent.
    void finish();

private:
    struct Shot {
        gl::Buffer pixels;   // pixel-pack buffer, RGBA8, reallocated only when the size changes
        std::filesystem::path file;
        glm::ivec2 size{0};
        std::string line;
    };
    using Ring = gl::FenceRing<Shot>;
    void retire(Ring::Slot& s);
    void collect(bool wait);

    Ring ring_;
    std::vector<std::shared_future<void>> writes_;   // in the order taken
};

}  // namespace ranryu::app
