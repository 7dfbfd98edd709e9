#include "validation/snapshots.h"

#include <bit>
#include <utility>

#include "sim/fluid.h"

namespace ranryu::validation {
namespace {

std::size_t record_bytes(const sim::Fluid& fluid, unsigned arrays) {
    return std::size_t(std::popcount(arrays & 7u)) * fluid.count() * sizeof(glm::vec4);
}

}  // namespace

ParticleSnapshots::ParticleSnapshots(const sim::Fluid& fluid, unsigned arrays, Consumer on_snapshot)
    : fluid_(fluid),
      arrays_(arrays & 7u),
      on_snapshot_(std::move(on_snapshot)),
      readback_(record_bytes(fluid, arrays), kDepth, "validation.snapshots", [this](std::uint64_t tag, const void* bytes) {
          // The record holds the asked arrays in the order positions, densities, velocities.
          const auto* at = static_cast<const glm::vec4*>(bytes);
          const std::size_t n = fluid_.count();
          View view{tag, {}, {}, {}};
          for (const auto& [bit, field] : {std::pair{kPositions, &View::positions}, std::pair{kDensities, &View::densities},
                                           std::pair{kVelocities, &View::velocities}})
              if (arrays_ & bit) {
                  view.*field = std::span<const glm::vec4>(at, n);
                  at += n;
              }
          if (on_snapshot_) on_snapshot_(view);
      }) {}

void ParticleSnapshots::capture(std::uint64_t tag) {
    const std::size_t bytes = fluid_.count() * sizeof(glm::vec4);
    gl::AsyncReadback::Part parts[3];
    std::size_t k = 0;
    if (arrays_ & kPositions) parts[k++] = {&fluid_.positions(), 0, bytes};
    if (arrays_ & kDensities) parts[k++] = {&fluid_.densities(), 0, bytes};
    if (arrays_ & kVelocities) parts[k++] = {&fluid_.velocities(), 0, bytes};
    readback_.copy(std::span<const gl::AsyncReadback::Part>(parts, k), tag);
}

std::size_t ParticleSnapshots::poll() { return readback_.poll(); }
std::size_t ParticleSnapshots::drain() { return readback_.drain(); }

}  // namespace ranryu::validation
