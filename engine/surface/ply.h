#pragma once
// PLY export (Turk 1994, the Stanford format): binary little-endian, one vertex element with float
// x y z nx ny nz, one face element with a `list uchar int vertex_indices` of three indices each.
#include <filesystem>
#include <span>

#include <glm/glm.hpp>

#include "surface/mesh.h"

namespace ranryu::surface {

// Writes "<path>.tmp" and renames it over `path`, so a reader never sees half a file. Throws
// ranryu::Error naming the file when it cannot be written, when normals and positions differ in
// count, or when a triangle refers past the last vertex.
void write_ply(const std::filesystem::path& path, std::span<const glm::vec3> positions,
               std::span<const glm::vec3> normals, std::span<const glm::uvec3> triangles);
void write_ply(const std::filesystem::path& path, const IndexedMesh& mesh);

}  // namespace ranryu::surface
