#pragma once
// The fluid's particle arrays after a frame, for validation cases that measure the whole state every
// frame without stopping the frame loop: capture() queues one record of the chosen arrays, tagged;
// the consumer receives each record from poll() or drain(), frames late, oldest first, as views into
// a buffer it must not keep beyond the call. No GPU -> CPU copy waits (gl::AsyncReadback's contract:
// only a ring still wholly in flight holds capture() back), and nothing is allocated after the
// constructor.
#include <cstdint>
#include <functional>
#include <span>

#include <glm/vec4.hpp>

#include "gl/readback.h"

namespace ranryu::sim {
class Fluid;
}

namespace ranryu::validation {

class ParticleSnapshots {
public:
    // Which arrays a record holds (a bit set); each is count() vec4s in the fluid's current order.
    enum Arrays : unsigned { kPositions = 1u, kDensities = 2u, kVelocities = 4u };
    // The arrays not asked for are empty.
    struct View {
        std::uint64_t tag;
        std::span<const glm::vec4> positions, densities, velocities;
    };
    using Consumer = std::function<void(const View&)>;

    // Records of `arrays` of `fluid`, which must outlive this.
    ParticleSnapshots(const sim::Fluid& fluid, unsigned arrays, Consumer on_snapshot);

    // Queues the arrays as they are after the commands issued so far.
    void capture(std::uint64_t tag);
    // Hands over every finished record; returns how many.
    std::size_t poll();
    // Waits for every queued record and hands them over (the end of a case's run).
    std::size_t drain();
    // Tests: records are handed over only when their slot is reused or drained, the latest the ring
    // allows (gl::AsyncReadback::hand_over_only_when_reused), so a case's result must not depend on when.
    void hand_over_late(bool on) { readback_.hand_over_only_when_reused(on); }

private:
    static constexpr int kDepth = 3;
    const sim::Fluid& fluid_;
    unsigned arrays_;
    Consumer on_snapshot_;
    gl::AsyncReadback readback_;
};

}  // namespace ranryu::validation
