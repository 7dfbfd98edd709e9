#include "gl/readback.h"

#include <string>
#include <utility>

namespace ranryu::gl {

AsyncReadback::AsyncReadback(std::size_t record_bytes, int depth, std::string_view name, Consumer on_record)
    : on_record_(std::move(on_record)), bytes_(record_bytes), ring_(std::size_t(depth < 1 ? 1 : depth)),
      scratch_(record_bytes) {
    for (std::size_t i = 0; i < ring_.size(); ++i)
        ring_[i].buffer = Buffer(bytes_, GL_STREAM_READ, nullptr, std::string(name) + "." + std::to_string(i));
}

void AsyncReadback::copy(const Buffer& src, std::size_t offset, std::uint64_t tag) {
    poll();
    Slot& s = ring_[next_];
    if (s.busy) {   // the GPU is a whole ring behind: wait (back-pressure), then hand the record over
        s.fence.wait();
        hand_over(s);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, src.id());
    glBindBuffer(GL_COPY_WRITE_BUFFER, s.buffer.id());
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, GLintptr(offset), 0, GLsizeiptr(bytes_));
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    s.fence.insert();
    s.tag = tag;
    s.busy = true;
    next_ = (next_ + 1) % ring_.size();
}

void AsyncReadback::hand_over(Slot& s) {
    s.buffer.read_bytes(scratch_.data(), bytes_);   // the fence has signalled: no wait
    s.fence.reset();
    s.busy = false;
    if (on_record_) on_record_(s.tag, scratch_.data());
    oldest_ = std::size_t(&s - ring_.data() + 1) % ring_.size();
}

std::size_t AsyncReadback::poll() {
    std::size_t n = 0;
    while (ring_[oldest_].busy && ring_[oldest_].fence.signaled()) {
        hand_over(ring_[oldest_]);
        ++n;
    }
    return n;
}

std::size_t AsyncReadback::drain() {
    std::size_t n = 0;
    while (ring_[oldest_].busy) {
        ring_[oldest_].fence.wait();
        hand_over(ring_[oldest_]);
        ++n;
    }
    return n;
}

}  // namespace ranryu::gl
