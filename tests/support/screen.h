#pragma once
// The raster tests' CPU view of a frame: the ray through a window position (pixel centres at +½) and
// the window position of a world point, for a view_proj matrix and an image size, in doubles.
#include <glm/glm.hpp>

namespace ranryu::test {

struct Screen {
    glm::dmat4 view_proj;
    int width, height;
    glm::dmat4 inv = glm::inverse(view_proj);

    // The unit direction of the ray through window position (x, y).
    glm::dvec3 ray(double x, double y) const {
        const glm::dvec2 ndc(2.0 * x / width - 1.0, 2.0 * y / height - 1.0);
        const glm::dvec4 a = inv * glm::dvec4(ndc, -1.0, 1.0), b = inv * glm::dvec4(ndc, 1.0, 1.0);
        return glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
    }
    // Window position of a world point.
    glm::dvec2 window(glm::dvec3 p) const {
        const glm::dvec4 c = view_proj * glm::dvec4(p, 1.0);
        return {(0.5 * c.x / c.w + 0.5) * width, (0.5 * c.y / c.w + 0.5) * height};
    }
};

}  // namespace ranryu::test
