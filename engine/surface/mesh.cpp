#include "surface/mesh.h"

#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <utility>

namespace ranryu::surface {
namespace {

struct Bits {
    std::uint32_t x, y, z;
    bool operator==(const Bits&) const = default;
};
struct HashBits {
    std::size_t operator()(const Bits& b) const {
        std::uint64_t h = b.x;
        h = h * 0x9E3779B97F4A7C15ull ^ b.y;
        h = h * 0x9E3779B97F4A7C15ull ^ b.z;
        return std::size_t(h ^ (h >> 29));
    }
};
Bits bits(glm::vec3 p) {
    Bits b;
    std::memcpy(&b.x, &p.x, 4);
    std::memcpy(&b.y, &p.y, 4);
    std::memcpy(&b.z, &p.z, 4);
    return b;
}

struct HashEdge {
    std::size_t operator()(const std::pair<std::uint32_t, std::uint32_t>& e) const {
        return std::size_t((std::uint64_t(e.first) << 32 | e.second) * 0x9E3779B97F4A7C15ull >> 7);
    }
};

}  // namespace

IndexedMesh weld(std::span<const gpu::MeshVertex> soup) {
    IndexedMesh m;
    std::unordered_map<Bits, std::uint32_t, HashBits> index;
    index.reserve(soup.size() / 2);
    m.triangles.reserve(soup.size() / 3);
    for (std::size_t t = 0; t + 2 < soup.size(); t += 3) {
        glm::uvec3 tri;
        for (int v = 0; v < 3; ++v) {
            const glm::vec3 p(soup[t + std::size_t(v)].position);
            auto [it, fresh] = index.try_emplace(bits(p), std::uint32_t(m.positions.size()));
            if (fresh) {
                m.positions.push_back(p);
                m.normals.emplace_back(soup[t + std::size_t(v)].normal);
            }
            tri[v] = it->second;
        }
        m.triangles.push_back(tri);
    }
    return m;
}

MeshMeasures measure(std::span<const gpu::MeshVertex> soup) {
    MeshMeasures r;
    for (std::size_t t = 0; t + 2 < soup.size(); t += 3) {
        const glm::dvec3 a(soup[t].position), b(soup[t + 1].position), c(soup[t + 2].position);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        r.area += 0.5 * glm::length(n);
        r.volume += glm::dot(a, n) / 6.0;
    }
    return r;
}

Topology topology(const IndexedMesh& mesh) {
    Topology t;
    t.faces = mesh.triangles.size();
    std::unordered_map<std::pair<std::uint32_t, std::uint32_t>, int, HashEdge> directed, undirected;
    std::vector<bool> used(mesh.positions.size(), false);
    for (const glm::uvec3& tri : mesh.triangles) {
        if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) ++t.degenerate_faces;
        for (int v = 0; v < 3; ++v) {
            const std::uint32_t a = tri[v], b = tri[(v + 1) % 3];
            used[a] = true;
            ++directed[{a, b}];
            ++undirected[{std::min(a, b), std::max(a, b)}];
        }
    }
    for (bool u : used) t.vertices += u ? 1 : 0;
    t.edges = undirected.size();
    for (const auto& [e, n] : undirected) t.boundary_or_nonmanifold_edges += n != 2 ? 1 : 0;
    for (const auto& [e, n] : directed) {
        const auto back = directed.find({e.second, e.first});
        if (n != 1 || back == directed.end() || back->second != 1) ++t.misoriented_edges;
    }
    return t;
}

}  // namespace ranryu::surface
