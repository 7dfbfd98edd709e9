#pragma once
// Particle files: one frame's particles as a binary point cloud, for ParaView, Blender and Houdini.
//
//   PLY (Turk 1994): "format binary_little_endian 1.0", one `vertex` element, one record per particle:
//       float x y z vx vy vz      position (m), velocity (m/s)
//       float density pressure    ρ (kg/m³), p (Pa)                    SPH scenes
//       uchar level               E_i, the sub-particle level split to  sub-particles on
//       float energy              ê_i, the wavelet energy (m²/s²)       turbulence on
//   VTK XML PolyData (.vtp, version 1.0, LittleEndian, header_type UInt64): Points (Float32 × 3) and
//       PointData arrays velocity (Float32 × 3), density, pressure, energy (Float32) and level
//       (UInt8), as present above, plus Verts (Int32 connectivity 0..n-1 and offsets 1..n) so that
//       ParaView draws every point. Every array is in the appended section, raw: per array a UInt64
//       byte count, then its bytes; a DataArray's offset counts bytes from the "_" that opens it.
//
// The particles come in the GPU's order: the neighbour grid's cell order of the frame's last sort
// (sim/fluid.h), not the order of the scene's blocks; a particle's index changes from frame to frame.
// Density and pressure are those of the frame's last step (its density pass, and for DFSPH the
// pressure written at the step's end); the level and ê those of the frame's end (sub-particles'
// classification and the last step's wavelet pass).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::record {

enum class ParticleFormat { ply, vtp };
// "ply" or "vtp"; anything else throws InputError naming `option` and the value.
ParticleFormat parse_particle_format(const std::string& text, const std::string& option);
const char* extension(ParticleFormat f);   // "ply", "vtp"

// One frame's particles as the GPU keeps them. Spans left empty are not written.
struct ParticleFrame {
    std::span<const glm::vec4> positions;    // xyz (m)
    std::span<const glm::vec4> velocities;   // xyz (m/s)
    std::span<const glm::vec4> densities;    // x ρ, y p (sim::Fluid::densities())
    std::span<const std::uint32_t> levels;   // L_i | E_i << 8 (turbulence::Subparticles::levels()): E_i is written
    std::span<const glm::vec4> energies;     // w ê_i (turbulence::WaveletAnalysis::energy())
};

// The names of the per-particle values a frame of this shape writes, in file order (run.json):
// "x", "y", "z", "vx", "vy", "vz", then "density", "pressure", "level", "energy" as present.
std::vector<std::string> particle_fields(bool density, bool level, bool energy);

// Writes the file whole or not at all ("<path>.tmp", renamed). `scratch` is the caller's reusable
// buffer (its storage is kept from frame to frame). Throws ranryu::Error naming the file.
void write_particles(ParticleFormat format, const std::filesystem::path& path, const ParticleFrame& frame,
                     std::vector<char>& scratch);

}  // namespace ranryu::record
