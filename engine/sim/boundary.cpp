#include "sim/boundary.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"

namespace ranryu::sim {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kShellPitch = 0.7f;   // a sphere's shell points, in spacings (see sample_boundary)

// Cells of at most `dx` filling [lo, hi] exactly: ceil(extent / dx) of them (the 1e-4 absorbs the
// rounding of extents that are whole multiples of dx), at least one.
int cells(float lo, float hi, float dx) { return std::max(1, int(std::ceil((hi - lo) / dx - 1e-4f))); }

// Lattice coordinates along one axis for the interval [lo, hi]: cells() sites inside, at
// lo + (i + 1/2)·pitch, and `layers` sites of pitch dx beyond each end, at lo - (l + 1/2)·dx and
// hi + (l + 1/2)·dx; with each site's pitch.
struct Axis {
    std::vector<float> at, pitch;
    std::vector<int> side;   // -1 below lo, 0 inside, +1 above hi
};
Axis axis(float lo, float hi, float dx, int layers) {
    Axis a;
    auto put = [&](float x, float p, int side) { a.at.push_back(x), a.pitch.push_back(p), a.side.push_back(side); };
    for (int l = layers - 1; l >= 0; --l) put(lo - (float(l) + 0.5f) * dx, dx, -1);
    const int n = cells(lo, hi, dx);
    const float pitch = (hi - lo) / float(n);   // <= dx, and fits the interval: no gap at the far end
    for (int i = 0; i < n; ++i) put(lo + (float(i) + 0.5f) * pitch, pitch, 0);
    for (int l = 0; l < layers; ++l) put(hi + (float(l) + 0.5f) * dx, dx, +1);
    return a;
}

// N points spread evenly over the sphere of radius r about c (the Fibonacci lattice: equal-area bands
// in z, successive points turned by the golden angle), each standing for volume `cell`.
template <class Out>
void fibonacci_shell(glm::vec3 c, float r, int n, float cell, Out& out) {
    const float golden = kPi * (3.0f - std::sqrt(5.0f));
    for (int k = 0; k < n; ++k) {
        const float z = 1.0f - (2.0f * float(k) + 1.0f) / float(n);
        const float rho = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = golden * float(k);
        out.emplace_back(c + r * glm::vec3(rho * std::cos(phi), z, rho * std::sin(phi)), cell);
    }
}

}  // namespace

int boundary_layers(float spacing, float support) { return int(std::ceil(support / spacing)) + 1; }

namespace {

// The tank's three axes of sites.
struct TankAxes {
    Axis x, y, z;
    TankAxes(const scene::Scene& s, int layers)
        : x(axis(s.tank_min.x, s.tank_max.x, s.spacing, layers)), y(axis(s.tank_min.y, s.tank_max.y, s.spacing, layers)),
          z(axis(s.tank_min.z, s.tank_max.z, s.spacing, layers)) {}
};

// A sphere's boundary: shells of thickness dx from the surface inward, `layers` of them or down to
// the centre, each a Fibonacci lattice at its mid radius (half a spacing inside the surface for the
// outer one, as on a flat wall) sharing the shell's volume equally. Its points are kShellPitch apart,
// finer than the fluid: an irregular lattice as coarse as dx leaves holes where the boundary density
// a resting fluid particle sees drops by 25 % (a Fibonacci lattice's local spacing varies); at 0.7 dx
// it stays within about 15 % of the flat wall's.
template <class Out>
void sample_sphere(glm::vec3 center, float radius, float dx, int layers, Out& out) {
    for (int l = 0; l < layers; ++l) {
        const float r_out = radius - float(l) * dx, r_in = radius - float(l + 1) * dx;
        if (r_out <= 0.0f) break;
        if (r_in <= 0.0f) {   // what is left is a ball thinner than a shell: one particle at the centre
            out.emplace_back(center, 4.0f / 3.0f * kPi * r_out * r_out * r_out);
            break;
        }
        const float r = 0.5f * (r_in + r_out), pitch = kShellPitch * dx;
        const int n = std::max(1, int(std::lround(4.0f * kPi * r * r / (pitch * pitch))));
        const float volume = 4.0f / 3.0f * kPi * (r_out * r_out * r_out - r_in * r_in * r_in);
        fibonacci_shell(center, r, n, volume / float(n), out);
    }
}

// Calls out.emplace_back(vec3, w) for every obstacle's boundary particle, then the paddle's (parked),
// in sample_boundary()'s order.
template <class Out>
void walk_obstacles(const scene::Scene& s, int layers, Out& out) {
    const float dx = s.spacing;
    const float depth = float(layers) * dx;
    for (const scene::Obstacle& o : s.obstacles) {
        if (o.kind == scene::Obstacle::Kind::box) {
            // Lattice sites inside the box within `depth` of its surface (all of them in a box thinner
            // than 2·depth): the outer layer half a pitch inside every face, edges and corners included.
            const glm::ivec3 n(cells(o.min.x, o.max.x, dx), cells(o.min.y, o.max.y, dx), cells(o.min.z, o.max.z, dx));
            const glm::vec3 pitch = (o.max - o.min) / glm::vec3(n);
            const float cell = pitch.x * pitch.y * pitch.z;
            for (int k = 0; k < n.z; ++k)
                for (int j = 0; j < n.y; ++j)
                    for (int i = 0; i < n.x; ++i) {
                        const glm::vec3 p = o.min + (glm::vec3(float(i), float(j), float(k)) + 0.5f) * pitch;
                        const glm::vec3 d = glm::min(p - o.min, o.max - p);
                        if (std::min({d.x, d.y, d.z}) < depth) out.emplace_back(p, cell);
                    }
        } else {
            sample_sphere(o.center, o.radius, dx, layers, out);
        }
    }
    if (s.paddle_radius > 0.0f) sample_sphere(paddle_park(s), s.paddle_radius, dx, layers, out);
}

// Calls out.emplace_back(x, y, z, w) or out.emplace_back(vec3, w) for every boundary particle, in
// sample_boundary()'s order: the tank's shell, less the part above the top unless the tank is
// closed, then the obstacles and the paddle.
template <class Out>
void walk_boundary(const scene::Scene& s, int layers, Out& out) {
    const TankAxes t(s, layers);
    const Axis &ax = t.x, &ay = t.y, &az = t.z;
    for (std::size_t k = 0; k < az.at.size(); ++k)
        for (std::size_t j = 0; j < ay.at.size(); ++j) {
            if (ay.side[j] > 0 && !s.tank_closed) continue;
            for (std::size_t i = 0; i < ax.at.size(); ++i)
                if (ax.side[i] != 0 || ay.side[j] != 0 || az.side[k] != 0)
                    out.emplace_back(ax.at[i], ay.at[j], az.at[k], ax.pitch[i] * ay.pitch[j] * az.pitch[k]);
        }
    walk_obstacles(s, layers, out);
}


struct Counter {
    std::size_t n = 0;
    template <class... A>
    void emplace_back(A&&...) { ++n; }
};

}  // namespace

std::vector<glm::vec4> sample_boundary(const scene::Scene& s, int layers) {
    std::vector<glm::vec4> out;
    walk_boundary(s, layers, out);
    return out;
}

std::size_t boundary_count(const scene::Scene& s, int layers) {
    // The tank's shell by counting (the memory check asks at tens of millions), the obstacles by walking.
    const TankAxes t(s, layers);
    const auto inside = [](const Axis& a) { return std::size_t(std::count(a.side.begin(), a.side.end(), 0)); };
    const std::size_t nx = t.x.at.size(), nz = t.z.at.size(), hole = inside(t.x) * inside(t.z);
    Counter c;
    for (int side : t.y.side) {
        if (side > 0 && !s.tank_closed) continue;
        c.n += nx * nz - (side == 0 ? hole : 0);
    }
    walk_obstacles(s, layers, c);
    return c.n;
}

std::vector<glm::vec4> obstacle_shapes(const scene::Scene& s) {
    std::vector<glm::vec4> out{glm::vec4(float(s.obstacles.size()), 0.0f, 0.0f, 0.0f)};
    for (const scene::Obstacle& o : s.obstacles) {
        if (o.kind == scene::Obstacle::Kind::box) {
            out.emplace_back(o.min, 0.0f);
            out.emplace_back(o.max, 0.0f);
        } else {
            out.emplace_back(o.center, 1.0f);
            out.emplace_back(o.radius, 0.0f, 0.0f, 0.0f);
        }
    }
    if (s.paddle_radius > 0.0f) {
        out[0].x += 1.0f;
        out.emplace_back(paddle_park(s), 2.0f);
        out.emplace_back(0.0f);
    }
    return out;
}

std::vector<glm::vec4> paddle_offsets(const scene::Scene& s, int layers) {
    std::vector<glm::vec4> out;
    if (s.paddle_radius > 0.0f) sample_sphere(glm::vec3(0.0f), s.paddle_radius, s.spacing, layers, out);
    return out;
}

glm::vec3 paddle_park(const scene::Scene& s) {
    const glm::vec3 c = 0.5f * (s.tank_min + s.tank_max);
    // 1 m and the sphere's radius below the floor's boundary layers: no fluid or wall particle is
    // within a support of it (the guard stops a particle that far below the floor).
    return glm::vec3(c.x, s.tank_min.y - 1.0f - s.paddle_radius - 8.0f * s.spacing, c.z);
}

float paddle_radius_for(const scene::Scene& s) {
    const glm::vec3 e = s.tank_max - s.tank_min;
    const float largest = std::max({e.x, e.y, e.z}), smallest = std::min({e.x, e.y, e.z});
    return std::max(std::min(0.1f * largest, 0.45f * smallest), 3.0f * s.spacing);
}

}  // namespace ranryu::sim
