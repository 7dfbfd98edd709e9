// `ranryu export-field`: samples the turbulence field y of docs/METHOD.md §4
// (engine/turbulence/noise.h) on an N³ grid on the GPU and writes it as a NumPy .npy v1.0 file:
// float32, shape (N, N, N, 3), C order, f[i, j, k] = y(L·(i, j, k)/N). Written to a temporary file
// beside the target, then renamed over it.
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "commands.h"
#include "core/error.h"
#include "profile/gpu_timer.h"
#include "turbulence/noise.h"

namespace ranryu::app {
namespace {

static_assert(std::endian::native == std::endian::little, ".npy descr '<f4' assumes a little-endian host");

// The .npy v1.0 header: magic, version, little-endian header length, then the dict padded with spaces
// and a newline so that the data starts at a multiple of 64 bytes.
std::string npy_header(int n) {
    const std::string s = std::to_string(n);
    std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + s + ", " + s + ", " + s + ", 3), }";
    const std::size_t unpadded = 10 + dict.size() + 1;
    dict.append((64 - unpadded % 64) % 64, ' ');
    dict += '\n';
    std::string h = "\x93NUMPY";
    h += char(1);
    h += char(0);
    h += char(dict.size() & 0xFF);
    h += char((dict.size() >> 8) & 0xFF);
    return h + dict;
}

}  // namespace

int export_field(const Options& o) {
    namespace fs = std::filesystem;
    const fs::path out(o.out);
    // Refuse before any GPU work: an existing file is earlier output (a folder is never replaced), and
    // the file must be writable where it goes.
    if (fs::exists(out) && !fs::is_directory(out) && !o.force)
        throw InputError("--out " + o.out + ": the file exists; not overwriting it (use --force)");
    profile::check_writable(out, "--out " + o.out);   // a folder, a missing folder, no write access

    const shader::FileSource shaders = shader_source(o);
    auto ctx = headless(o);
    profile::GpuTimer timer(1, 4);
    const turbulence::NoiseTiles tiles = turbulence::NoiseTiles::generate(o.seed);
    turbulence::CurlNoise noise(shaders, timer, tiles);
    turbulence::FieldSpec spec;
    spec.dims = glm::uvec3(std::uint32_t(o.field_size));
    spec.origin = glm::vec3(0.0f);
    spec.spacing = o.extent / float(o.field_size);
    spec.lmin = o.lmin;
    spec.lmax = o.lmax;
    spec.beta = o.beta;
    const std::vector<float> field = noise.sample_to_host(spec);
    timer.drain();
    double ms = 0.0;
    for (const auto& p : timer.passes())
        for (double v : p.ms) ms += v;

    // Octave i has tile cells of 2^-i m and features down to 2 cells; fewer than 2 samples per cell aliases.
    const double per_cell = std::ldexp(double(o.field_size) / double(o.extent), -o.lmax);
    if (per_cell < 2.0)
        std::printf("ranryu: note: octave %d has %.2f samples per noise cell (under 2): its finest features alias on this grid\n",
                    o.lmax, per_cell);
    const std::string header = npy_header(o.field_size);
    fs::path tmp = out;
    tmp += ".tmp" + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) throw InputError("--out " + o.out + ": cannot write the file (" + std::strerror(errno) + ")");
        f.write(header.data(), std::streamsize(header.size()));
        f.write(reinterpret_cast<const char*>(field.data()), std::streamsize(field.size() * sizeof(float)));
        if (!f.flush()) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw InputError("--out " + o.out + ": cannot write the file");
        }
    }
    std::error_code ec;
    fs::rename(tmp, out, ec);
    if (ec) {
        std::error_code ignore;
        fs::remove(tmp, ignore);
        throw InputError("--out " + o.out + ": cannot write the file (" + ec.message() + ")");
    }
    std::printf("wrote %s: float32 (%d, %d, %d, 3), extent %g m, octaves %d:%d, beta %g, seed %u, tile %d^3; noise.sample %.3f ms\n",
                o.out.c_str(), o.field_size, o.field_size, o.field_size, double(o.extent), o.lmin, o.lmax, double(o.beta),
                o.seed, tiles.n, ms);
    return 0;
}

}  // namespace ranryu::app
