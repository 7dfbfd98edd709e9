#pragma once
// Frames handed from the render thread to writer threads, each written only once it is known sound.
//
// The render thread takes a free buffer (acquire), fills it, and submits it as a frame; writer
// threads call `write(frame, buffer)` for the submitted frames in frame order, each once the caller
// has validated it (validate_through), and drop those from discard_from() on: nothing drawn after
// an instability reaches disk. Buffers are the caller's own preallocated storage, named here by
// index. acquire() waits while every buffer is queued (the writers, or the records that validate
// frames, are behind), calling `pump` meanwhile so that the caller can collect those records
// instead of deadlocking. Used through record::ReadbackQueue by record::Recorder (PNG, video),
// record::MeshExporter (PLY) and record::ParticleExporter (PLY, VTP).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace ranryu::record {

class GatedWriter {
public:
    // `write` may throw; the first failure is kept and finish() reports it. Without `gated` every
    // frame counts as validated.
    using Write = std::function<void(std::uint64_t frame, std::size_t buffer)>;
    GatedWriter(std::size_t buffers, int threads, bool gated, Write write, std::function<void()> pump);
    ~GatedWriter();
    GatedWriter(const GatedWriter&) = delete;
    GatedWriter& operator=(const GatedWriter&) = delete;

    std::size_t acquire();
    void submit(std::uint64_t frame, std::size_t buffer);   // frames in increasing order
    void release(std::size_t buffer);                       // acquired but not submitted
    void fail(const std::string& what);                     // a failure found by the caller

    void validate_through(std::uint64_t frame);   // frames up to and including `frame` may be written
    void discard_from(std::uint64_t frame);       // frames from `frame` on never are
    // Writes every validated frame, drops the rest, stops the threads. Throws ranryu::Error with
    // the first failure. Idempotent.
    void finish();
    std::uint64_t written() const;

private:
    struct Job {
        std::uint64_t frame;
        std::size_t buffer;
    };
    void loop();

    Write write_;
    std::function<void()> pump_;
    bool gated_;
    std::vector<std::size_t> free_;
    std::deque<Job> jobs_;
    mutable std::mutex mutex_;
    std::condition_variable work_, done_;
    std::uint64_t validated_end_;   // frames below this may be written
    std::uint64_t discard_from_ = ~0ull;
    std::uint64_t written_ = 0;
    std::string error_;
    bool stopping_ = false;
    std::vector<std::thread> threads_;
};

}  // namespace ranryu::record
