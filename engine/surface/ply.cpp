#include "surface/ply.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/whole_file.h"

namespace ranryu::surface {
namespace {

// Appends little-endian bytes whatever the host's byte order.
void put_u32(std::vector<char>& out, std::uint32_t v) {
    for (int b = 0; b < 4; ++b) out.push_back(char((v >> (8 * b)) & 0xFFu));
}
void put_f32(std::vector<char>& out, float f) {
    std::uint32_t v;
    std::memcpy(&v, &f, sizeof v);
    put_u32(out, v);
}

}  // namespace

void write_ply(const std::filesystem::path& path, std::span<const glm::vec3> positions,
               std::span<const glm::vec3> normals, std::span<const glm::uvec3> triangles) {
    const std::string where = "cannot write mesh " + path.string() + ": ";
    if (normals.size() != positions.size())
        throw Error(where + std::to_string(normals.size()) + " normals for " + std::to_string(positions.size()) + " vertices");
    if (positions.size() > std::size_t(INT32_MAX)) throw Error(where + "too many vertices for int indices");

    std::string header = "ply\nformat binary_little_endian 1.0\ncomment ranryu liquid surface (marching cubes)\n";
    header += "element vertex " + std::to_string(positions.size()) + "\n";
    for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) header += std::string("property float ") + p + "\n";
    header += "element face " + std::to_string(triangles.size()) + "\n";
    header += "property list uchar int vertex_indices\nend_header\n";

    std::vector<char> body;
    body.reserve(positions.size() * 24 + triangles.size() * 13);
    for (std::size_t i = 0; i < positions.size(); ++i) {
        for (int a = 0; a < 3; ++a) put_f32(body, positions[i][a]);
        for (int a = 0; a < 3; ++a) put_f32(body, normals[i][a]);
    }
    for (const glm::uvec3& t : triangles) {
        body.push_back(char(3));
        for (int a = 0; a < 3; ++a) {
            if (t[a] >= positions.size())
                throw Error(where + "a triangle refers to vertex " + std::to_string(t[a]) + " of " +
                            std::to_string(positions.size()));
            put_u32(body, t[a]);
        }
    }

    write_whole_file(path, {header, std::string_view(body.data(), body.size())}, where);
}

void write_ply(const std::filesystem::path& path, const IndexedMesh& mesh) {
    write_ply(path, mesh.positions, mesh.normals, mesh.triangles);
}

}  // namespace ranryu::surface
