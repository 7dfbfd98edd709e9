#include "record/particle_files.h"

#include <bit>
#include <cstring>
#include <functional>

#include "core/error.h"
#include "core/whole_file.h"
#include "shared/bindings.h"

namespace ranryu::record {
namespace {

// The files are little-endian; values are copied as the host holds them.
static_assert(std::endian::native == std::endian::little, "particle files: a big-endian host would need byte swaps");

// One per-particle value of the file: its name, its VTK type, its components, the bytes of one
// component, and how to put particle i's components at `dst`.
struct Field {
    const char* name;
    const char* vtk_type;
    int components;
    std::size_t bytes;   // of one component
    std::function<void(std::size_t i, char* dst)> put;
};

template <class T>
void put(char*& dst, T v) {
    std::memcpy(dst, &v, sizeof v);
    dst += sizeof v;
}

// The file's values in order, positions first. Checks that every span present holds n particles.
std::vector<Field> fields_of(const ParticleFrame& f, const std::filesystem::path& path) {
    const std::size_t n = f.positions.size();
    auto check = [&](std::size_t size, const char* what) {
        if (size != 0 && size != n)
            throw Error("cannot write particles " + path.string() + ": " + std::to_string(size) + " " + what + " for " +
                        std::to_string(n) + " positions");
    };
    check(f.velocities.size(), "velocities");
    check(f.densities.size(), "densities");
    check(f.levels.size(), "levels");
    check(f.energies.size(), "energies");
    if (f.velocities.size() != n) throw Error("cannot write particles " + path.string() + ": no velocities");
    auto vec3 = [](std::span<const glm::vec4> v) {
        return [v](std::size_t i, char* dst) {
            for (int a = 0; a < 3; ++a) put(dst, v[i][a]);
        };
    };
    std::vector<Field> fields = {{"Points", "Float32", 3, 4, vec3(f.positions)},
                                 {"velocity", "Float32", 3, 4, vec3(f.velocities)}};
    if (!f.densities.empty()) {
        fields.push_back({"density", "Float32", 1, 4, [d = f.densities](std::size_t i, char* dst) { put(dst, d[i].x); }});
        fields.push_back({"pressure", "Float32", 1, 4, [d = f.densities](std::size_t i, char* dst) { put(dst, d[i].y); }});
    }
    if (!f.levels.empty())
        fields.push_back({"level", "UInt8", 1, 1, [l = f.levels](std::size_t i, char* dst) {
                              put(dst, std::uint8_t(l[i] >> RANRYU_SUBPARTICLE_SPLIT_SHIFT));
                          }});
    if (!f.energies.empty())
        fields.push_back({"energy", "Float32", 1, 4, [e = f.energies](std::size_t i, char* dst) { put(dst, e[i].w); }});
    return fields;
}

void write_ply(const std::filesystem::path& path, const ParticleFrame& frame, std::vector<char>& body) {
    const std::vector<Field> fields = fields_of(frame, path);
    const std::size_t n = frame.positions.size();
    std::string header = "ply\nformat binary_little_endian 1.0\n"
                         "comment ranryu particles, in the GPU's neighbour-sort order\n"
                         "element vertex " + std::to_string(n) + "\n";
    std::size_t record = 0;
    for (const Field& f : fields) {
        const char* type = f.bytes == 1 ? "uchar" : "float";
        if (f.components == 3) {
            const bool position = std::strcmp(f.name, "Points") == 0;
            for (const char* axis : {"x", "y", "z"})
                header += std::string("property ") + type + " " + (position ? "" : "v") + axis + "\n";
        } else {
            header += std::string("property ") + type + " " + f.name + "\n";
        }
        record += f.bytes * std::size_t(f.components);
    }
    header += "end_header\n";
    body.resize(n * record);   // the storage stays from frame to frame
    char* dst = body.data();
    for (std::size_t i = 0; i < n; ++i)
        for (const Field& f : fields) {
            f.put(i, dst);
            dst += f.bytes * std::size_t(f.components);
        }
    write_whole_file(path, {header, std::string_view(body.data(), body.size())}, "cannot write particles " + path.string() + ": ");
}

void write_vtp(const std::filesystem::path& path, const ParticleFrame& frame, std::vector<char>& body) {
    const std::vector<Field> fields = fields_of(frame, path);
    const std::size_t n = frame.positions.size();
    // The appended blocks: every field's, then the Verts' connectivity (i) and offsets (i + 1).
    std::size_t total = 0;
    for (const Field& f : fields) total += 8 + n * f.bytes * std::size_t(f.components);
    total += 2 * (8 + n * 4);
    body.resize(total);   // the storage stays from frame to frame
    char* dst = body.data();
    std::vector<std::size_t> offsets;
    auto block = [&](std::size_t bytes) {
        offsets.push_back(std::size_t(dst - body.data()));
        put(dst, std::uint64_t(bytes));
    };
    for (const Field& f : fields) {
        const std::size_t each = f.bytes * std::size_t(f.components);
        block(n * each);
        for (std::size_t i = 0; i < n; ++i, dst += each) f.put(i, dst);
    }
    for (std::int32_t first : {0, 1}) {
        block(n * 4);
        for (std::size_t i = 0; i < n; ++i) put(dst, std::int32_t(i) + first);
    }

    auto array = [&](const Field& f, std::size_t offset) {
        return std::string("        <DataArray type=\"") + f.vtk_type + "\" Name=\"" + f.name + "\" NumberOfComponents=\"" +
               std::to_string(f.components) + "\" format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
    };
    const std::string count = std::to_string(n);
    std::string xml = "<?xml version=\"1.0\"?>\n"
                      "<!-- ranryu particles, in the GPU's neighbour-sort order -->\n"
                      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                      "  <PolyData>\n"
                      "    <Piece NumberOfPoints=\"" + count + "\" NumberOfVerts=\"" + count +
                      "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
    xml += std::string("      <PointData Vectors=\"velocity\"") + (frame.densities.empty() ? "" : " Scalars=\"density\"") + ">\n";
    for (std::size_t k = 1; k < fields.size(); ++k) xml += "  " + array(fields[k], offsets[k]);
    xml += "      </PointData>\n      <Points>\n  " + array(fields[0], offsets[0]) + "      </Points>\n      <Verts>\n";
    const Field connectivity{"connectivity", "Int32", 1, 4, {}}, offs{"offsets", "Int32", 1, 4, {}};
    xml += "  " + array(connectivity, offsets[fields.size()]) + "  " + array(offs, offsets[fields.size() + 1]);
    xml += "      </Verts>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";
    static constexpr std::string_view tail = "\n  </AppendedData>\n</VTKFile>\n";
    write_whole_file(path, {xml, std::string_view(body.data(), body.size()), tail},
                     "cannot write particles " + path.string() + ": ");
}

}  // namespace

ParticleFormat parse_particle_format(const std::string& text, const std::string& option) {
    if (text == "ply") return ParticleFormat::ply;
    if (text == "vtp") return ParticleFormat::vtp;
    throw InputError(option + " " + text + ": unknown particle format; expected ply or vtp");
}

const char* extension(ParticleFormat f) { return f == ParticleFormat::ply ? "ply" : "vtp"; }

std::vector<std::string> particle_fields(bool density, bool level, bool energy) {
    std::vector<std::string> names = {"x", "y", "z", "vx", "vy", "vz"};
    if (density) names.insert(names.end(), {"density", "pressure"});
    if (level) names.push_back("level");
    if (energy) names.push_back("energy");
    return names;
}

void write_particles(ParticleFormat format, const std::filesystem::path& path, const ParticleFrame& frame,
                     std::vector<char>& scratch) {
    if (format == ParticleFormat::ply) write_ply(path, frame, scratch);
    else write_vtp(path, frame, scratch);
}

}  // namespace ranryu::record
