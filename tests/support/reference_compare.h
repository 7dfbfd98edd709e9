#pragma once
// What the GL tests that compare GPU passes with the double-precision CPU references share
// (dfsph_test.cpp, pbf_test.cpp): the float unit roundoff and the per-term constant their bounds are
// written in (dfsph_test.cpp's header derives the bounds), the GPU's vec4 arrays as doubles, and the
// flags a density pass stores in density.w (glsl/sim/fluid/fluid.glsl).
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::test {

constexpr double kU = std::numeric_limits<float>::epsilon() / 2.0;   // float's unit roundoff u = 2^-24
constexpr double kC = 16.0;   // relative error of one kernel term (a value or gradient times a few products), in u

inline glm::dvec3 d3(const glm::vec4& v) { return glm::dvec3(glm::vec3(v)); }
inline std::vector<glm::dvec3> d3(const std::vector<glm::vec4>& v) {
    std::vector<glm::dvec3> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = d3(v[i]);
    return out;
}
inline double vec_error(const glm::vec4& got, const glm::dvec3& want) { return glm::length(d3(got) - want); }

inline std::uint32_t flags_of(const glm::vec4& density) {
    std::uint32_t f;
    std::memcpy(&f, &density.w, sizeof f);
    return f;
}

}  // namespace ranryu::test
