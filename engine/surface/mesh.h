#pragma once
// CPU tools for the triangle soup that marching cubes writes: welding into an indexed mesh (for
// export and for topology checks), area and volume, and the watertightness counts.
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "shared/bindings.h"

namespace ranryu::surface {

struct IndexedMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;       // one per position
    std::vector<glm::uvec3> triangles;    // counter-clockwise seen from outside
};

// Merges vertices whose positions are bit-identical (marching cubes' shared edge vertices are);
// each merged vertex keeps the first normal. Vertex order: first appearance.
IndexedMesh weld(std::span<const gpu::MeshVertex> soup);

struct MeshMeasures {
    double area = 0.0;     // sum of triangle areas
    double volume = 0.0;   // enclosed volume by the divergence theorem: sum of x0 · (x1-x0)x(x2-x0) / 6
};
MeshMeasures measure(std::span<const gpu::MeshVertex> soup);

struct Topology {
    std::size_t vertices = 0, edges = 0, faces = 0;
    std::size_t boundary_or_nonmanifold_edges = 0;   // edges not in exactly two triangles
    std::size_t misoriented_edges = 0;               // directed edges not matched by one in the other direction
    std::size_t degenerate_faces = 0;                // triangles with a repeated vertex
    long euler() const { return long(vertices) - long(edges) + long(faces); }
    bool watertight() const { return boundary_or_nonmanifold_edges == 0 && misoriented_edges == 0 && degenerate_faces == 0; }
};
Topology topology(const IndexedMesh& mesh);

}  // namespace ranryu::surface
