#pragma once
// Asynchronous GPU -> CPU copies of small records (diagnostics, counters): copy() queues a
// glCopyBufferSubData into the next buffer of a ring and fences it; poll() hands over, oldest first,
// the records whose fences have signalled. Nothing waits on the GPU unless the whole ring is still
// in flight when copy() needs a slot (back-pressure; with depth ≥ 3 only a GPU frames behind does
// that). Records arrive in the order they were queued, frames late.
#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <vector>

#include "gl/fence_ring.h"
#include "gl/objects.h"

namespace ranryu::gl {

class AsyncReadback {
public:
    // `on_record(tag, bytes)` receives every record, oldest first, from poll(), drain() or copy().
    using Consumer = std::function<void(std::uint64_t tag, const void* bytes)>;
    AsyncReadback(std::size_t record_bytes, int depth, std::string_view name, Consumer on_record);

    // Queues a copy of [offset, offset + record_bytes) of `src`, tagged with `tag`.
    void copy(const Buffer& src, std::size_t offset, std::uint64_t tag);
    // One part of a record gathered from several buffers: `bytes` from `offset` of `src`.
    struct Part {
        const Buffer* src;
        std::size_t offset, bytes;
    };
    // Queues one record made of `parts`, one after another; their bytes must sum to record_bytes.
    void copy(std::span<const Part> parts, std::uint64_t tag);
    // Hands over every finished record; returns how many.
    std::size_t poll();
    // Waits for every queued record and hands them over. Shutdown and tests only.
    std::size_t drain();
    // On: records are handed over only when copy() needs their slot again, or by drain(), never by
    // poll(): the latest the ring allows, as the slowest GPU would return them. For tests of code that
    // must not depend on when records come back (sim/fluid.h planning_record()).
    void hand_over_only_when_reused(bool on) { only_when_reused_ = on; }

private:
    void hand_over(FenceRing<Buffer>::Slot& s);
    Consumer on_record_;

    std::size_t bytes_;
    FenceRing<Buffer> ring_;
    std::vector<std::uint8_t> scratch_;
    bool only_when_reused_ = false;
};

}  // namespace ranryu::gl
