#pragma once
// Fresh random inputs for the reference tests. Each test case makes one Random and INFOs its seed, so
// a failure can be replayed by constructing Random with that seed.
#include <cstdint>
#include <random>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace ranryu::reference {

struct Random {
    uint64_t seed;
    std::mt19937_64 engine;

    Random() : Random(std::random_device{}()) {}
    explicit Random(uint64_t s) : seed(s), engine(s) {}

    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine); }  // [lo, hi]
    double normal() { return std::normal_distribution<double>(0.0, 1.0)(engine); }
    glm::dvec3 in_box(double half) { return {uniform(-half, half), uniform(-half, half), uniform(-half, half)}; }
    // Uniform on the sphere of rotations (a normalised Gaussian quaternion).
    glm::dmat3 rotation() { return glm::mat3_cast(glm::normalize(glm::dquat(normal(), normal(), normal(), normal()))); }
};

}  // namespace ranryu::reference
