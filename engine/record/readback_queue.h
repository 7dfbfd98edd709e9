#pragma once
// What every asynchronous export shares (record::Recorder's PNGs and video, record::MeshExporter,
// record::ParticleExporter): a gl::FenceRing of GPU copies, each retired (read back) into a CPU frame
// once its fence has signalled, and the record::GatedWriter whose threads write those frames once
// the caller has validated them. The owner fills the slots and its CPU frames; this keeps the order:
//
//     Slot& s = queue.acquire();   // the next slot (retired first if the GPU is a whole ring behind)
//     ... queue the copies into s.data ...
//     queue.submit();              // fences it as the next frame, retires what the GPU has finished
//     queue.finish();              // end of a run: retires every slot, writes the validated frames
//
// `retire(slot)` takes a CPU frame from writer().acquire(), reads the slot into it and submits it
// (or fails and releases it). CPU frames: one per writer thread, the ring's worth retiring, and for a
// gated run the frames held until their records arrive (those come a few frames late).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "gl/fence_ring.h"
#include "record/gated_writer.h"

namespace ranryu::record {

template <class Copies>
class ReadbackQueue {
public:
    using Slot = typename gl::FenceRing<Copies>::Slot;   // tag: the frame

    ReadbackQueue(std::string owner, int depth, int threads, bool gated, GatedWriter::Write write,
                  std::function<void()> pump, std::function<void(Slot&)> retire)
        : owner_(std::move(owner)), ring_(std::size_t(std::max(depth, 1))), retire_(std::move(retire)),
          buffers_(std::size_t(std::max(threads, 1)) + ring_.size() + (gated ? 8 : 0)),
          writer_(std::make_unique<GatedWriter>(buffers_, threads, gated, std::move(write), std::move(pump))) {}

    std::vector<Slot>& slots() { return ring_.slots(); }
    std::size_t buffers() const { return buffers_; }   // CPU frames the owner allocates, named 0..buffers()-1
    GatedWriter& writer() { return *writer_; }
    const GatedWriter& writer() const { return *writer_; }
    std::uint64_t captured() const { return captured_; }

    Slot& acquire() {
        if (finished_) throw Error(owner_ + ": capture after finish");
        return ring_.acquire(retire_);
    }
    void submit() { ring_.submit(captured_++, retire_); }
    // The frame number of the first capture (a run resumed from a checkpoint goes on from its frame).
    // Before any capture.
    void start_at(std::uint64_t frame) {
        if (captured_ != first_) throw Error(owner_ + ": start_at after a capture");
        captured_ = first_ = frame;
    }
    void validate_through(std::uint64_t frame) { writer_->validate_through(frame); }
    void discard_from(std::uint64_t frame) { writer_->discard_from(frame); }
    // Waits for every copy and every validated frame's file, drops the rest. Throws ranryu::Error
    // with the first write that failed. Idempotent.
    void finish() {
        if (finished_) return;
        finished_ = true;
        ring_.drain(retire_);
        writer_->finish();
    }

private:
    std::string owner_;
    gl::FenceRing<Copies> ring_;
    std::function<void(Slot&)> retire_;
    std::size_t buffers_;
    std::unique_ptr<GatedWriter> writer_;
    std::uint64_t captured_ = 0, first_ = 0;
    bool finished_ = false;
};

// For the owners' destructors, which must not throw: runs `finish`, printing a failure to stderr.
template <class F>
void finish_or_report(F&& finish) noexcept {
    try {
        finish();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ranryu: %s\n", e.what());
    }
}

}  // namespace ranryu::record
