#include "gl/readback.h"

#include "core/error.h"

#include <string>
#include <utility>

namespace ranryu::gl {

AsyncReadback::AsyncReadback(std::size_t record_bytes, int depth, std::string_view name, Consumer on_record)
    : on_record_(std::move(on_record)), bytes_(record_bytes), ring_(std::size_t(depth < 1 ? 1 : depth), std::string(name)),
      scratch_(record_bytes) {
    for (std::size_t i = 0; i < ring_.size(); ++i)
        ring_.slots()[i].data = Buffer(bytes_, GL_STREAM_READ, nullptr, std::string(name) + "." + std::to_string(i));
}

void AsyncReadback::copy(const Buffer& src, std::size_t offset, std::uint64_t tag) {
    const Part whole{&src, offset, bytes_};
    copy(std::span<const Part>(&whole, 1), tag);
}

void AsyncReadback::copy(std::span<const Part> parts, std::uint64_t tag) {
    std::size_t total = 0;
    for (const Part& p : parts) total += p.bytes;
    if (total != bytes_)
        throw Error("AsyncReadback: a record of " + std::to_string(total) + " bytes where " + std::to_string(bytes_) + " were set");
    auto retire = [this](FenceRing<Buffer>::Slot& s) { hand_over(s); };
    const Buffer& dst = ring_.acquire(retire).data;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::size_t at = 0;
    for (const Part& p : parts) {
        copy_buffer(*p.src, dst, p.bytes, p.offset, at);
        at += p.bytes;
    }
    if (only_when_reused_) ring_.fence(tag);
    else ring_.submit(tag, retire);
}

void AsyncReadback::hand_over(FenceRing<Buffer>::Slot& s) {
    s.data.read_own_bytes(scratch_.data(), bytes_);   // the fence has signalled: no wait
    if (on_record_) on_record_(s.tag, scratch_.data());
}

std::size_t AsyncReadback::poll() {
    if (only_when_reused_) return 0;
    return ring_.poll([this](FenceRing<Buffer>::Slot& s) { hand_over(s); });
}

std::size_t AsyncReadback::drain() {
    return ring_.drain([this](FenceRing<Buffer>::Slot& s) { hand_over(s); });
}

}  // namespace ranryu::gl
