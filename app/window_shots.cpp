#include "window_shots.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <utility>

#include "record/png.h"

namespace ranryu::app {
WindowShots::~WindowShots() {
    try {
        finish();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ranryu: %s\n", e.what());
    }
}

void WindowShots::take(std::filesystem::path file, glm::ivec2 fb, std::string line) {
    Ring::Slot& s = ring_.acquire([this](Ring::Slot& done) { retire(done); });
    const std::size_t bytes = std::size_t(fb.x) * std::size_t(fb.y) * 4;
    if (s.data.pixels.size() != bytes) s.data.pixels = gl::Buffer(bytes, GL_STREAM_READ, nullptr, "window screenshot");
    s.data.file = std::move(file);
    s.data.size = fb;
    s.data.line = std::move(line);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, s.data.pixels.id());
    glReadPixels(0, 0, fb.x, fb.y, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);   // into the buffer: no wait
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    ring_.submit(0, [this](Ring::Slot& done) { retire(done); });
}

void WindowShots::retire(Ring::Slot& s) {
    // The fence has signalled: mapping does not wait. The rows are flipped (GL's first row is the
    // bottom) on the writer's thread, with the PNG.
    const Shot& shot = s.data;
    const std::size_t row = std::size_t(shot.size.x) * 4, bytes = row * std::size_t(shot.size.y);
    std::vector<std::uint8_t> raw(bytes);
    glBindBuffer(GL_COPY_READ_BUFFER, shot.pixels.id());
    if (const void* p = glMapBufferRange(GL_COPY_READ_BUFFER, 0, GLsizeiptr(bytes), GL_MAP_READ_BIT)) {
        std::memcpy(raw.data(), p, bytes);
        glUnmapBuffer(GL_COPY_READ_BUFFER);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    // Written in parallel, printed in the order taken: each line waits for the one before it.
    std::shared_future<void> before = writes_.empty() ? std::shared_future<void>() : writes_.back();
    writes_.push_back(std::async(std::launch::async, [raw = std::move(raw), file = shot.file, size = shot.size, line = shot.line, row,
                                                      before] {
                          std::vector<std::uint8_t> flipped(raw.size());
                          for (int y = 0; y < size.y; ++y)
                              std::copy_n(raw.data() + std::size_t(size.y - 1 - y) * row, row, flipped.data() + std::size_t(y) * row);
                          record::write_png(file, size.x, size.y, flipped.data());
                          if (before.valid()) before.wait();
                          std::printf("%s\n", line.c_str());
                          std::fflush(stdout);
                      }).share());
}

void WindowShots::collect(bool wait) {
    for (auto it = writes_.begin(); it != writes_.end();) {
        if (wait || it->wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
            std::shared_future<void> done = std::move(*it);
            it = writes_.erase(it);
            done.get();   // rethrows the write's failure
        } else {
            ++it;
        }
    }
}

void WindowShots::poll() {
    ring_.poll([this](Ring::Slot& done) { retire(done); });
    collect(false);
}

void WindowShots::finish() {
    ring_.drain([this](Ring::Slot& done) { retire(done); });
    collect(true);
}

}  // namespace ranryu::app
