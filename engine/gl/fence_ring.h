#pragma once
// A ring of slots, each filled by GPU commands and fenced, handed back in the order they were
// filled once their fences signal: the mechanism under every asynchronous readback here
// (gl::AsyncReadback, and record::ReadbackQueue under the recorder and the exporters).
//
//     Slot& s = ring.acquire(retire);   // the next slot; if still in flight, waits and retires it
//     ... queue the GPU commands that fill s.data ...
//     ring.submit(tag, retire);         // fences s, then retires every finished slot, oldest first
//     ring.fence(tag);                  // fences s alone (slots retire at acquire() or drain())
//     ring.poll(retire);                // retires finished slots without filling one
//     ring.drain(retire);               // end of a run: waits for and retires them all
//
// `retire(Slot&)` reads the slot's data back (its fence has signalled, so nothing waits). The CPU
// waits only when the whole ring is still in flight at acquire(): back-pressure, not a stall.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "gl/objects.h"

namespace ranryu::gl {

template <class Data>
class FenceRing {
public:
    struct Slot {
        Data data;
        Fence fence;
        std::uint64_t tag = 0;   // what the filler says the slot holds (a frame number)
        bool busy = false;
    };

    // `name`: what the slots hold, for the report of a fence that does not signal (gl/faults.h).
    explicit FenceRing(std::size_t depth, std::string name = "readback") : slots_(depth < 1 ? 1 : depth), name_(std::move(name)) {}

    std::vector<Slot>& slots() { return slots_; }
    std::size_t size() const { return slots_.size(); }

    template <class Retire>
    Slot& acquire(Retire&& retire) {
        Slot& s = slots_[next_];
        if (s.busy) {   // the GPU is a whole ring behind
            s.fence.wait(what(s));
            hand_over(s, retire);
        }
        return s;
    }

    template <class Retire>
    void submit(std::uint64_t tag, Retire&& retire) {
        fence(tag);
        poll(retire);
    }

    void fence(std::uint64_t tag) {
        Slot& s = slots_[next_];
        s.fence.insert();
        s.tag = tag;
        s.busy = true;
        next_ = (next_ + 1) % slots_.size();
    }

    // Retires, oldest first, every slot whose fence has signalled; stops at the first in flight.
    template <class Retire>
    std::size_t poll(Retire&& retire) {
        std::size_t n = 0;
        for (std::size_t k = 0; k < slots_.size(); ++k) {
            Slot& s = slots_[(next_ + k) % slots_.size()];
            if (!s.busy) continue;
            if (!s.fence.signaled()) break;
            hand_over(s, retire);
            ++n;
        }
        return n;
    }

    template <class Retire>
    std::size_t drain(Retire&& retire) {
        std::size_t n = 0;
        for (std::size_t k = 0; k < slots_.size(); ++k) {
            Slot& s = slots_[(next_ + k) % slots_.size()];
            if (!s.busy) continue;
            s.fence.wait(what(s));
            hand_over(s, retire);
            ++n;
        }
        return n;
    }

private:
    std::string what(const Slot& s) const { return name_ + " of frame " + std::to_string(s.tag); }
    template <class Retire>
    void hand_over(Slot& s, Retire& retire) {
        retire(s);
        s.fence.reset();
        s.busy = false;
    }

    std::vector<Slot> slots_;
    std::string name_;
    std::size_t next_ = 0;
};

}  // namespace ranryu::gl
