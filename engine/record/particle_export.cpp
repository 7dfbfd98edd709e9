#include "record/particle_export.h"


#include "core/error.h"
#include "frame/pipeline.h"
#include "turbulence/force.h"
#include "record/recorder.h"

namespace ranryu::record {
namespace {

// The arrays by number: 0 positions, 1 velocities, 2 densities, 3 levels, 4 energies.
constexpr int kArrays = 5;
constexpr const char* kNames[kArrays] = {"positions", "velocities", "densities", "levels", "energies"};
std::size_t bytes_per_particle(int k) { return k == 3 ? sizeof(std::uint32_t) : sizeof(glm::vec4); }
const gl::Buffer* source(const ParticleBuffers& b, int k) {
    const gl::Buffer* all[kArrays] = {b.positions, b.velocities, b.densities, b.levels, b.energies};
    return all[k];
}

}  // namespace

ParticleBuffers particle_buffers(const frame::Pipeline& p) {
    ParticleBuffers b{&p.positions(), &p.velocities()};
    if (const sim::Simulation* sim = p.simulation()) {
        b.densities = &sim->fluid().densities();
        if (const turbulence::TurbulenceForce* force = sim->turbulence()) b.energies = &force->wavelet().energy();
    }
    if (const turbulence::Subparticles* sub = p.subparticles()) b.levels = &sub->levels();
    return b;
}

ParticleExporter::ParticleExporter(profile::GpuTimer& timer, std::filesystem::path dir, ParticleFormat format,
                                   std::size_t count, const ParticleBuffers& shape, bool gated,
                                   std::function<void()> pump, int ring)
    : timer_(timer), pass_(timer.pass("particle-readback")), dir_(std::move(dir)), format_(format), count_(count),
      density_(shape.densities), level_(shape.levels), energy_(shape.energies),
      queue_("ParticleExporter", ring, 1, gated, [this](std::uint64_t, std::size_t b) { write(b); }, std::move(pump),
             [this](Slot& s) { retire(s); }) {
    const bool present[kArrays] = {true, true, density_, level_, energy_};
    for (std::size_t i = 0; i < queue_.slots().size(); ++i) {
        Arrays& a = queue_.slots()[i].data;
        gl::Buffer* copies[kArrays] = {&a.positions, &a.velocities, &a.densities, &a.levels, &a.energies};
        for (int k = 0; k < kArrays; ++k)
            if (present[k])
                *copies[k] = gl::Buffer(count_ * bytes_per_particle(k), GL_STREAM_READ, nullptr,
                                        std::string("particle-readback.") + kNames[k] + "." + std::to_string(i));
    }
    // The CPU frames, each allocated here once: the frame path allocates nothing.
    buffers_.resize(queue_.buffers());
    for (Frame& f : buffers_) {
        f.positions.resize(count_);
        f.velocities.resize(count_);
        if (density_) f.densities.resize(count_);
        if (level_) f.levels.resize(count_);
        if (energy_) f.energies.resize(count_);
    }
}

ParticleExporter::~ParticleExporter() { finish_or_report([this] { finish(); }); }

void ParticleExporter::capture(const ParticleBuffers& b) {
    const bool present[kArrays] = {true, true, density_, level_, energy_};
    for (int k = 0; k < kArrays; ++k) {
        const gl::Buffer* src = source(b, k);
        if ((src != nullptr) != present[k] || (src && src->size() < count_ * bytes_per_particle(k)))
            throw Error(std::string("ParticleExporter: the ") + kNames[k] + " buffer is not the one the exporter was made for");
    }
    Slot& s = queue_.acquire();
    {
        auto pass = timer_.scope(pass_);
        // The simulation's passes wrote these as storage buffers: make those writes visible to the copies.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        gl::Buffer* copies[kArrays] = {&s.data.positions, &s.data.velocities, &s.data.densities, &s.data.levels,
                                       &s.data.energies};
        for (int k = 0; k < kArrays; ++k)
            if (present[k]) gl::copy_buffer(*source(b, k), *copies[k], copies[k]->size());
    }
    queue_.submit();
}

void ParticleExporter::retire(Slot& s) {
    const std::size_t buffer = queue_.writer().acquire();
    Frame& f = buffers_[buffer];
    f.frame = s.tag;
    // The fence has signalled: these reads do not wait.
    const std::pair<const gl::Buffer*, void*> copies[kArrays] = {
        {&s.data.positions, f.positions.data()}, {&s.data.velocities, f.velocities.data()},
        {&s.data.densities, f.densities.data()}, {&s.data.levels, f.levels.data()},
        {&s.data.energies, f.energies.data()}};
    for (const auto& [copy, dst] : copies)
        if (*copy) copy->read_own_bytes(dst, copy->size());
    queue_.writer().submit(s.tag, buffer);
}

// On the writer thread (the only one, so scratch_ needs no lock).
void ParticleExporter::write(std::size_t buffer) {
    const Frame& f = buffers_[buffer];
    const ParticleFrame frame{f.positions, f.velocities, f.densities, f.levels, f.energies};
    write_particles(format_, dir_ / frame_name(f.frame, extension(format_), "particles"), frame, scratch_);
}

void ParticleExporter::validate_through(std::uint64_t frame) { queue_.validate_through(frame); }
void ParticleExporter::discard_from(std::uint64_t frame) { queue_.discard_from(frame); }
void ParticleExporter::finish() { queue_.finish(); }

std::vector<std::string> ParticleExporter::fields() const { return particle_fields(density_, level_, energy_); }

}  // namespace ranryu::record
