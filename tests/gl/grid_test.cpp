// The neighbour grid of the SPH model (engine/sim/grid.*, glsl/sim/grid/) after Fluid::rebuild_grid(),
// against brute force on the CPU, for both key layouts (linear, Morton) and both sorts (radix,
// bitonic):
//   - every particle's neighbours found through the 27 cells around its cell (read-back cell ranges,
//     sorted positions, the key function of glsl/sim/grid.glsl redone on the CPU) are exactly
//     reference::neighbours() on the same positions: every j with |x_i - x_j| < h;
//   - the sorted keys are the keys of the sorted positions, ascending; the cell ranges are exactly
//     the runs of equal keys for the cells that have particles, and every other cell's entry is one
//     the readers reject: the fluid's ranges are not cleared between substeps (grid.h), so an empty
//     cell may keep a stale entry, which sim/fluid/fluid.glsl's fluid_run() takes only if the sorted key at
//     its start is the cell's own. Each case rebuilds twice, from two different states, so that stale
//     entries exist when the second is checked;
//   - the sorted arrays are a permutation of the input (multisets of positions equal), each velocity
//     travels with its position, and the order is (key, input index) ascending: the radix is stable
//     and the bitonic orders equal keys by value, which is the input index.
// Everything here is exact (integer keys, ranges, permutations; neighbour sets decided in double on
// the same float positions), so the inputs are drawn so that no decision sits on a knife edge: no pair
// distance within 1e-5·h of h and no coordinate within 1e-5 cell of a cell face.
#include "support/gl_fixture.h"
#include "support/sph_rig.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "profile/gpu_timer.h"
#include "reference/sph_reference.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/fluid.h"

namespace {

using ranryu::profile::GpuTimer;
using ranryu::sim::GridLayout;
using ranryu::sim::Fluid;

// An SPH scene and its model; the model samples its boundary and computes psi at construction.
struct Rig : ranryu::test::SphRig {
    explicit Rig(const std::string& json) : SphRig(json, "grid_test") {}
};

// Tank 0.3 m a side, spacing 0.03 m (h = 0.06 m): an 8x8x8 block, 512 particles.
std::string scene_json(const std::string& keys, const std::string& sort) {
    return R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
               "sph": {"neighbour_keys": ")" + keys + R"(", "sort": ")" + sort + R"("},
               "particles": {"spacing": 0.03, "blocks": [{"min": [0, 0, 0], "max": [0.24, 0.24, 0.24]}]}})";
}

// The cell and key of glsl/sim/grid.glsl, in the same float operations.
glm::ivec3 cell_of(const GridLayout& g, glm::vec3 x) {
    const glm::ivec3 c(glm::floor((x - g.origin) / g.cell));
    return glm::clamp(c, glm::ivec3(0), glm::ivec3(g.dims) - 1);
}
std::uint32_t key_of(const GridLayout& g, glm::ivec3 c) {
    const glm::uvec3 u(c);
    if (g.morton) return ranryu::sim::spread_bits(u.x) | (ranryu::sim::spread_bits(u.y) << 1) | (ranryu::sim::spread_bits(u.z) << 2);
    return u.x + g.dims.x * (u.y + g.dims.y * u.z);
}
bool inside(const GridLayout& g, glm::ivec3 c) {
    return glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThan(c, glm::ivec3(g.dims)));
}

std::vector<glm::dvec3> to_double(const std::vector<glm::vec4>& x) {
    std::vector<glm::dvec3> d(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) d[i] = glm::dvec3(glm::vec3(x[i]));
    return d;
}

// No pair distance within band·h of h, no coordinate within band (cells) of a face of its cell.
bool well_posed(const std::vector<glm::vec4>& x, const GridLayout& g, double h, double band) {
    const auto d = to_double(x);
    for (std::size_t i = 0; i < d.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            const double t = (d[i][a] - double(g.origin[a])) / double(g.cell);
            if (t < 0.0 || t >= double(g.dims[a])) continue;   // clamped to the edge cell: no face to sit on
            if (std::abs(t - std::round(t)) < band) return false;
        }
        for (std::size_t j = i + 1; j < d.size(); ++j)
            if (std::abs(glm::length(d[i] - d[j]) - h) < band * h) return false;
    }
    return true;
}

// The scene's lattice jittered by up to ±0.3 dx per axis and shuffled; a pair made coincident; and
// eight particles moved into a cluster above the top of the grid, whose cells are clamped to the top
// layer (fluid.cpp: "particles higher still share the top layer of cells: slower, never wrong").
// velocity.w = input index, so the sorted order can be traced back.
void random_state(ranryu::test::Random& rng, Rig& rig, std::vector<glm::vec4>& x, std::vector<glm::vec4>& v) {
    const float dx = rig.scene.spacing, h = 2.0f * dx;
    const GridLayout& g = rig.fluid.grid().layout();
    const std::vector<glm::vec4> lattice = rig.scene.initial_positions();
    const std::size_t n = lattice.size();
    REQUIRE(n > 20);
    const float top = g.origin.y + g.cell * float(g.dims.y);
    for (int attempt = 0; attempt < 100; ++attempt) {
        x = lattice;
        std::shuffle(x.begin(), x.end(), rng.engine());
        for (auto& p : x) p += glm::vec4(rng.uniform(-0.3f, 0.3f), rng.uniform(-0.3f, 0.3f), rng.uniform(-0.3f, 0.3f), 0.0f) * dx;
        const glm::vec3 cluster(rng.uniform(0.05f, 0.25f), top + 0.2f, rng.uniform(0.05f, 0.25f));
        for (std::size_t k = n - 8; k < n; ++k)
            x[k] = glm::vec4(cluster + glm::vec3(rng.uniform(-0.6f, 0.6f), rng.uniform(-0.6f, 0.6f), rng.uniform(-0.6f, 0.6f)) * h, 0.0f);
        x[1] = x[0];
        if (well_posed(x, g, double(h), 1e-5)) break;
        REQUIRE(attempt < 99);
    }
    v.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        v[i] = glm::vec4(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), float(i));
}

struct Snapshot {
    std::vector<glm::vec4> x, v;
    std::vector<std::uint32_t> keys, start, end;
};

Snapshot rebuild(Rig& rig, const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& v) {
    Fluid& sph = rig.fluid;
    sph.upload_state(x, v);
    rig.timer.begin_frame();
    sph.rebuild_grid();
    rig.timer.end_frame();
    const std::size_t n = sph.count(), keys = sph.grid().layout().key_count;
    Snapshot s{sph.positions().read<glm::vec4>(n), sph.velocities().read<glm::vec4>(n),
               sph.grid().sort().sorted_keys().read<std::uint32_t>(n), {}, {}};
    for (const glm::uvec2& r : sph.cell_ranges().cells.read<glm::uvec2>(keys)) s.start.push_back(r.x), s.end.push_back(r.y);
    return s;
}

void check_grid(const std::string& keys, const std::string& sort) {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed() << ", keys " << keys << ", sort " << sort);
    Rig rig(scene_json(keys, sort));
    Fluid& sph = rig.fluid;
    const GridLayout& g = sph.grid().layout();
    REQUIRE(g.morton == (keys == "morton"));
    const double h = 2.0 * double(rig.scene.spacing);
    REQUIRE(double(g.cell) == h);

    std::vector<glm::vec4> x, v;
    random_state(rng, rig, x, v);
    for (auto& p : x) p.x += 0.04f;   // a first state whose cells differ: leaves stale ranges behind
    rebuild(rig, x, v);
    random_state(rng, rig, x, v);
    const std::size_t n = x.size();
    const Snapshot s = rebuild(rig, x, v);

    // Permutation: equal multisets of positions, and each sorted (x, v) is the input pair it names.
    auto lexicographic = [](const glm::vec4& a, const glm::vec4& b) {
        return std::tie(a.x, a.y, a.z, a.w) < std::tie(b.x, b.y, b.z, b.w);
    };
    std::vector<glm::vec4> in_sorted = x, out_sorted = s.x;
    std::sort(in_sorted.begin(), in_sorted.end(), lexicographic);
    std::sort(out_sorted.begin(), out_sorted.end(), lexicographic);
    CHECK(in_sorted == out_sorted);
    std::vector<std::uint32_t> origin(n);
    std::size_t unpaired = 0;
    for (std::size_t i = 0; i < n; ++i) {
        origin[i] = std::uint32_t(s.v[i].w);
        if (origin[i] >= n || s.x[i] != x[origin[i]] || s.v[i] != v[origin[i]]) ++unpaired;
    }
    CHECK(unpaired == 0);
    std::vector<std::uint32_t> sorted_origin = origin;
    std::sort(sorted_origin.begin(), sorted_origin.end());
    std::vector<std::uint32_t> iota(n);
    std::iota(iota.begin(), iota.end(), 0u);
    CHECK(sorted_origin == iota);

    // Keys: the GPU's sorted keys are the CPU's keys of the sorted positions, ascending, ties in
    // input order; the ranges are the runs of equal keys.
    std::vector<std::uint32_t> key(n);
    std::size_t wrong_key = 0, misordered = 0;
    for (std::size_t i = 0; i < n; ++i) {
        key[i] = key_of(g, cell_of(g, glm::vec3(s.x[i])));
        wrong_key += key[i] != s.keys[i];
        if (i > 0 && std::tie(key[i - 1], origin[i - 1]) >= std::tie(key[i], origin[i])) ++misordered;
    }
    CHECK(wrong_key == 0);
    CHECK(misordered == 0);
    std::vector<std::uint32_t> start(g.key_count, 0u), end(g.key_count, 0u);
    std::vector<bool> occupied(g.key_count, false);
    for (std::size_t i = 0; i < n; ++i) {
        REQUIRE(key[i] < g.key_count);
        occupied[key[i]] = true;
        if (i == 0 || key[i - 1] != key[i]) start[key[i]] = std::uint32_t(i);
        if (i + 1 == n || key[i + 1] != key[i]) end[key[i]] = std::uint32_t(i + 1);
    }
    // The readers' test of an entry (fluid_run in sim/fluid/fluid.glsl): current iff the sorted key at its start is k.
    auto current = [&](std::size_t k) { return s.start[k] < n && s.keys[s.start[k]] == k; };
    std::size_t wrong_ranges = 0, first_wrong = g.key_count, cells = 0, stale = 0;
    for (std::size_t k = 0; k < g.key_count; ++k) {
        const bool ok = occupied[k] ? start[k] == s.start[k] && end[k] == s.end[k] && current(k) : !current(k);
        if (!ok) ++wrong_ranges, first_wrong = std::min(first_wrong, k);
        cells += occupied[k];
        stale += !occupied[k] && (s.start[k] != 0u || s.end[k] != 0u);
    }
    INFO("first wrong range at key " << first_wrong << "; " << cells << " cells occupied, " << stale
                                     << " empty cells with a stale entry, of " << g.key_count << " keys");
    CHECK(wrong_ranges == 0);

    // Neighbour sets through the 27 cells around each particle's cell vs brute force.
    const auto xd = to_double(s.x);
    const auto want = ranryu::reference::neighbours(xd, h);
    std::size_t wrong_sets = 0, pairs = 0, max_set = 0;
    std::string first;
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<std::uint32_t> found;
        const glm::ivec3 c = cell_of(g, glm::vec3(s.x[i]));
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 cc = c + glm::ivec3(dx, dy, dz);
                    if (!inside(g, cc)) continue;
                    const std::uint32_t k = key_of(g, cc);
                    if (!current(k)) continue;
                    for (std::uint32_t j = s.start[k]; j < s.end[k]; ++j)
                        if (glm::length(xd[i] - xd[j]) < h) found.push_back(j);
                }
        std::sort(found.begin(), found.end());
        pairs += want[i].size();
        max_set = std::max(max_set, want[i].size());
        if (found != want[i]) {
            if (!wrong_sets)
                first = "particle " + std::to_string(i) + ": grid finds " + std::to_string(found.size()) +
                        ", brute force " + std::to_string(want[i].size());
            ++wrong_sets;
        }
    }
    INFO(first);
    INFO(n << " particles, " << pairs << " neighbour pairs, largest set " << max_set);
    CHECK(wrong_sets == 0);
    CHECK(max_set >= 20);   // the jittered lattice gives sets of about 30: the check is not vacuous
    ranryu::test::require_no_gl_errors();
}

}  // namespace

TEST_CASE("grid: neighbour sets, keys, ranges and permutation, linear keys, radix sort", "[grid]") {
    check_grid("linear", "radix");
}

TEST_CASE("grid: neighbour sets, keys, ranges and permutation, Morton keys, radix sort", "[grid]") {
    check_grid("morton", "radix");
}

TEST_CASE("grid: neighbour sets, keys, ranges and permutation, linear keys, bitonic sort", "[grid]") {
    check_grid("linear", "bitonic");
}

TEST_CASE("grid: neighbour sets, keys, ranges and permutation, Morton keys, bitonic sort", "[grid]") {
    check_grid("morton", "bitonic");
}
