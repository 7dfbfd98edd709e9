// The marching cubes tables (glsl/surface/mc_tables.h, Lorensen & Cline 1987 in Bourke's 256-case form)
// and the CPU reference polygoniser (engine/surface/marching_cubes.h), without GL:
//   - every case lists exactly the edges whose corners differ in sign, at most 5 triangles;
//   - crack-free by construction: on each cube face the case's boundary segments depend only on that
//     face's four corners, and run in opposite directions in the two cells that share the face;
//   - oriented outward: the right-hand normal points to the outside corners;
//   - on analytic spheres and random fields the CPU mesh is watertight, with the expected error.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <vector>

#include "support/phi_fields.h"   // random fields; no context is made here
#include "surface/marching_cubes.h"
#include "surface/mesh.h"

using ranryu::surface::PhiGrid;

namespace {

auto triangles_of(int c) {
    std::vector<int> edges;
    const auto table = ranryu::surface::mc_triangle_table();
    for (int k = 0; k < 16 && table[std::size_t(c * 16 + k)] >= 0; ++k) edges.push_back(table[std::size_t(c * 16 + k)]);
    return edges;
}
glm::ivec3 corner(int c) {
    const auto t = ranryu::surface::mc_corner_table();
    return {t[std::size_t(3 * c)], t[std::size_t(3 * c + 1)], t[std::size_t(3 * c + 2)]};
}
std::pair<int, int> edge(int e) {
    const auto t = ranryu::surface::mc_edge_table();
    return {t[std::size_t(2 * e)], t[std::size_t(2 * e + 1)]};
}
// Twice the midpoint of edge e: integer coordinates 0..2.
glm::ivec3 edge_mid2(int e) { return corner(edge(e).first) + corner(edge(e).second); }

using ranryu::test::sphere;

}  // namespace

TEST_CASE("marching cubes table: shape, and each case cuts exactly the edges with a sign change", "[surface]") {
    const auto table = ranryu::surface::mc_triangle_table();
    for (int c = 0; c < 256; ++c) {
        INFO("case " << c);
        const auto t = triangles_of(c);
        CHECK(t.size() % 3 == 0);
        CHECK(t.size() <= 15);
        for (std::size_t k = t.size(); k < 16; ++k) CHECK(table[std::size_t(c * 16) + k] == -1);
        std::set<int> used(t.begin(), t.end()), cut;
        for (int e = 0; e < 12; ++e)
            if (((c >> edge(e).first) & 1) != ((c >> edge(e).second) & 1)) cut.insert(e);
        CHECK(used == cut);
    }
    // Corners are the unit cube's, edges join corners one step apart, lower corner first.
    std::set<std::tuple<int, int, int>> corners;
    for (int c = 0; c < 8; ++c) corners.insert({corner(c).x, corner(c).y, corner(c).z});
    CHECK(corners.size() == 8);
    for (int e = 0; e < 12; ++e) {
        const glm::ivec3 d = corner(edge(e).second) - corner(edge(e).first);
        CHECK(d.x + d.y + d.z == 1);
        CHECK(glm::all(glm::greaterThanEqual(d, glm::ivec3(0))));
    }
}

TEST_CASE("marching cubes table: cells sharing a face agree on it (no cracks, consistent orientation)", "[surface]") {
    // For each case, the directed edges of its triangles that have no reverse are the boundary of the
    // cell's patch. They must lie on cube faces; on a face they must be a function of the face's four
    // corner signs alone; and the cell on the other side (which sees the face as its opposite face)
    // must list them reversed. Then every shared edge of the whole mesh has one triangle on each side,
    // in opposite directions: watertight and consistently oriented for ANY field.
    using Segment = std::pair<glm::ivec2, glm::ivec2>;
    auto less = [](const Segment& a, const Segment& b) {
        return std::tie(a.first.x, a.first.y, a.second.x, a.second.y) < std::tie(b.first.x, b.first.y, b.second.x, b.second.y);
    };
    using Segments = std::set<Segment, decltype(less)>;
    std::map<std::pair<int, int>, Segments> seen;   // (axis, face pattern) -> segments as seen from the low side
    for (int c = 0; c < 256; ++c) {
        INFO("case " << c);
        const auto t = triangles_of(c);
        std::map<std::pair<int, int>, int> directed;
        for (std::size_t k = 0; k + 2 < t.size(); k += 3)
            for (int v = 0; v < 3; ++v) ++directed[{t[k + std::size_t(v)], t[k + std::size_t((v + 1) % 3)]}];
        std::vector<std::pair<int, int>> boundary;
        for (const auto& [e, n] : directed) {
            CHECK(n == 1);   // no directed edge twice within a cell
            if (!directed.count({e.second, e.first})) boundary.push_back(e);
        }
        for (const auto& [a, b] : boundary) {   // on some face: both midpoints share a coordinate 0 or 2
            const glm::ivec3 pa = edge_mid2(a), pb = edge_mid2(b);
            bool on_face = false;
            for (int k = 0; k < 3; ++k) on_face |= pa[k] == pb[k] && (pa[k] == 0 || pa[k] == 2);
            CHECK(on_face);
        }
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                int pattern = 0;   // the face's corner signs, keyed by their (u, v) position
                for (int q = 0; q < 8; ++q)
                    if (corner(q)[axis] == side) pattern |= ((c >> q) & 1) << (corner(q)[u] + 2 * corner(q)[v]);
                Segments segs(less);
                for (const auto& [a, b] : boundary) {
                    const glm::ivec3 pa = edge_mid2(a), pb = edge_mid2(b);
                    if (pa[axis] != 2 * side || pb[axis] != 2 * side) continue;
                    const glm::ivec2 qa(pa[u], pa[v]), qb(pb[u], pb[v]);
                    segs.insert(side == 0 ? Segment{qa, qb} : Segment{qb, qa});   // the high side's reversed
                }
                auto [it, fresh] = seen.try_emplace({axis, pattern}, segs);
                INFO("axis " << axis << ", side " << side << ", face pattern " << pattern);
                CHECK((fresh || it->second == segs));
            }
    }
    CHECK(seen.size() == 3 * 16);
}

TEST_CASE("marching cubes table: triangles face the outside corners", "[surface]") {
    // A single corner outside (and its complement, a single corner inside): the triangle's right-hand
    // normal points toward the outside, i.e. toward that corner (away from it for the complement).
    for (int q = 0; q < 8; ++q)
        for (int complement = 0; complement < 2; ++complement) {
            const int c = complement ? 255 ^ (1 << q) : 1 << q;
            const auto t = triangles_of(c);
            REQUIRE(t.size() == 3);
            const glm::vec3 a(edge_mid2(t[0])), b(edge_mid2(t[1])), d(edge_mid2(t[2]));
            const glm::vec3 n = glm::cross(b - a, d - a);
            const glm::vec3 to_corner = 2.0f * glm::vec3(corner(q)) - (a + b + d) / 3.0f;
            INFO("corner " << q << (complement ? ", complement" : ""));
            CHECK(glm::dot(n, to_corner) * (complement ? -1.0f : 1.0f) > 0.0f);
        }
}

TEST_CASE("CPU marching cubes: spheres are watertight, genus 0, with second-order area and volume error", "[surface]") {
    // φ = R - |x - c| with R = 6, 10, 16 node spacings, random centre and origin. Measured over many
    // random centres, the relative errors are -0.314 (h/R)^2 (area) and -0.594 (h/R)^2 (volume),
    // spread ±0.003: vertices lie inside the sphere (linear interpolation of the concave |x - c| along
    // an edge, and flat facets). Asserted: the coefficient within ±0.03 of those values.
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    for (float R : {6.0f, 10.0f, 16.0f}) {
        const float h = rng.uniform(0.005f, 0.05f);
        const glm::vec3 origin(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const auto n = std::uint32_t(2 * R + 5);
        const glm::vec3 centre = origin + h * (glm::vec3(float(n - 1) / 2) +
                                               glm::vec3(rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f)));
        const auto soup = ranryu::surface::polygonise_cpu(sphere(origin, h, glm::uvec3(n), centre, R * h));
        const auto m = ranryu::surface::measure(soup);
        const double r = R * h, pi = std::numbers::pi;
        const double area_coeff = (m.area / (4 * pi * r * r) - 1) * R * R;
        const double volume_coeff = (m.volume / (4.0 / 3.0 * pi * r * r * r) - 1) * R * R;
        INFO("R = " << R << " cells, h = " << h << ": area coefficient " << area_coeff << ", volume coefficient " << volume_coeff);
        CHECK(std::abs(area_coeff + 0.314) < 0.03);
        CHECK(std::abs(volume_coeff + 0.594) < 0.03);
        const auto topo = ranryu::surface::topology(ranryu::surface::weld(soup));
        CHECK(topo.watertight());
        CHECK(topo.euler() == 2);
    }
}

TEST_CASE("CPU marching cubes: random fields give closed, consistently oriented meshes", "[surface]") {
    // Random signs on every inner node (magnitudes in [0.1, 1], so vertices stay off the nodes), the
    // border outside: every ambiguous face and cube configuration turns up. Closed orientable surfaces
    // have an even Euler characteristic (2 - 2g per component).
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    for (int trial = 0; trial < 20; ++trial) {
        const glm::uvec3 dims(4 + rng.below(10), 4 + rng.below(10), 4 + rng.below(10));
        const glm::vec3 origin(rng.uniform(-1, 1));
        const PhiGrid g = ranryu::test::random_closed_field(rng, origin, rng.uniform(0.01f, 1.0f), dims);
        const auto soup = ranryu::surface::polygonise_cpu(g);
        const auto topo = ranryu::surface::topology(ranryu::surface::weld(soup));
        INFO("trial " << trial << ", dims " << dims.x << "x" << dims.y << "x" << dims.z << ", " << topo.faces << " triangles");
        CHECK(topo.boundary_or_nonmanifold_edges == 0);
        CHECK(topo.misoriented_edges == 0);
        CHECK(topo.degenerate_faces == 0);
        CHECK(topo.euler() % 2 == 0);
        CHECK(ranryu::surface::measure(soup).volume > 0.0);
    }
}
