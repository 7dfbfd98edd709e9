#include "frame/checkpoint.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/whole_file.h"
#include "profile/report.h"
#include "sim/state_io.h"

namespace ranryu::frame {
namespace {

using nlohmann::json;
constexpr char kMagic[8] = {'R', 'A', 'N', 'R', 'Y', 'U', 'C', 'P'};
constexpr std::uint32_t kFormat = 1;
// Why a checkpoint's entries would not match the pipeline's.
constexpr const char* kOther = " (the checkpoint is of another build, or another scene, spacing or solver)";
constexpr std::uint64_t kMaxHeader = 64ull << 20;   // the scene's text and the entries' list

// Saving: every entry's bytes, in the order persist() lists them.
class Saver final : public sim::StateIo {
public:
    void buffer(const std::string& name, gl::Buffer& b, std::size_t) override {
        std::vector<char>& bytes = add(name, b.size());
        if (b.size()) b.read_bytes(bytes.data(), b.size());
    }
    void bytes(const std::string& name, void* data, std::size_t size) override {
        std::memcpy(add(name, size).data(), data, size);
    }
    bool loading() const override { return false; }
    [[noreturn]] void refuse(const std::string& why) override { throw InputError(why); }
    std::vector<std::pair<std::string, std::vector<char>>> entries;

private:
    std::vector<char>& add(const std::string& name, std::size_t size) {
        for (const auto& e : entries)
            if (e.first == name) throw Error("checkpoint: the entry " + name + " is listed twice");
        entries.emplace_back(name, std::vector<char>(size));
        return entries.back().second;
    }
};

struct Entry {
    std::uint64_t offset = 0, bytes = 0;
    bool used = false;
};

struct Opened {
    json header;
    std::map<std::string, Entry> entries;
    std::uint64_t end = 0;   // where the entries end: the file's size
};

Opened open_file(std::ifstream& in, const std::filesystem::path& file, const std::string& what) {
    auto bad = [&](const std::string& why) { return InputError(what + ": " + why); };
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) throw bad("is a folder; name the checkpoint file");
    if (!std::filesystem::is_regular_file(file, ec)) throw bad("no such file");
    in.open(file, std::ios::binary);
    if (!in) throw bad("cannot read the file");
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    char magic[8] = {};
    std::uint32_t format = 0;
    std::uint64_t length = 0;
    in.read(magic, sizeof magic);
    if (!in || std::memcmp(magic, kMagic, sizeof magic) != 0) throw bad("not a ranryu checkpoint (it does not start with RANRYUCP)");
    in.read(reinterpret_cast<char*>(&format), sizeof format);
    in.read(reinterpret_cast<char*>(&length), sizeof length);
    if (!in) throw bad("truncated header");
    if (format != kFormat)
        throw bad("checkpoint format " + std::to_string(format) + "; this ranryu reads format " + std::to_string(kFormat));
    const std::uint64_t start = sizeof magic + sizeof format + sizeof length;
    if (length > kMaxHeader || start + length > size) throw bad("truncated header");
    std::string text(length, '\0');
    in.read(text.data(), std::streamsize(length));
    if (!in) throw bad("truncated header");
    Opened o;
    try {
        o.header = json::parse(text);
        std::uint64_t at = start + length;
        for (const json& e : o.header.at("entries")) {
            const std::uint64_t n = e.at("bytes").get<std::uint64_t>();
            o.entries[e.at("name").get<std::string>()] = Entry{at, n, false};
            at += n;
        }
        o.end = at;
        (void)o.header.at("scene").at("source").get<std::string>();
        // nlohmann converts a negative number to a huge unsigned one: the kinds are checked first.
        if (!o.header.at("frame").is_number_unsigned()) throw bad("malformed header: \"frame\" is not a whole number >= 0");
        if (!o.header.at("particles").is_number_unsigned()) throw bad("malformed header: \"particles\" is not a whole number >= 0");
        const double time = o.header.at("time").get<double>();
        if (!std::isfinite(time) || time < 0.0) throw bad("malformed header: \"time\" is not a finite time >= 0");
    } catch (const json::exception& e) {
        throw bad(std::string("malformed header: ") + e.what());
    }
    if (o.end != size)
        throw bad("the file is " + std::to_string(size) + " bytes; its header lists " + std::to_string(o.end) + " (truncated or damaged)");
    return o;
}

// Loading: each entry persist() lists, checked against the file's.
class Loader final : public sim::StateIo {
public:
    Loader(std::ifstream& in, Opened& o, std::string what) : in_(in), o_(o), what_(std::move(what)) {}
    void buffer(const std::string& name, gl::Buffer& b, std::size_t finite_vec4s) override {
        const Entry& e = find(name, b.size());
        if (!e.bytes) return;
        std::vector<char> bytes(e.bytes);
        read(e, bytes.data());
        const std::size_t n = std::min(bytes.size() / sizeof(float), 4 * finite_vec4s);
        for (std::size_t k = 0; k < n; ++k) {
            float x;
            std::memcpy(&x, bytes.data() + k * sizeof(float), sizeof x);
            if (!std::isfinite(x))
                throw InputError(what_ + ": entry " + name + " holds a non-finite value (element " + std::to_string(k / 4) +
                                 "): a damaged file");
        }
        b.upload(bytes.data(), bytes.size());
    }
    void bytes(const std::string& name, void* data, std::size_t size) override { read(find(name, size), data); }
    bool loading() const override { return true; }
    [[noreturn]] void refuse(const std::string& why) override { throw InputError(what_ + ": " + why); }
    void finish() const {
        for (const auto& [name, e] : o_.entries)
            if (!e.used) throw InputError(what_ + ": its entry " + name + " belongs to nothing in this run" + kOther);
    }

private:
    const Entry& find(const std::string& name, std::size_t size) {
        const auto it = o_.entries.find(name);
        if (it == o_.entries.end()) throw InputError(what_ + ": no entry " + name + kOther);
        if (it->second.bytes != size)
            throw InputError(what_ + ": entry " + name + " is " + std::to_string(it->second.bytes) + " bytes where this run has " +
                             std::to_string(size) + kOther);
        it->second.used = true;
        return it->second;
    }
    void read(const Entry& e, void* data) {
        in_.seekg(std::streamoff(e.offset));
        in_.read(static_cast<char*>(data), std::streamsize(e.bytes));
        if (!in_) throw InputError(what_ + ": cannot read its entries");
    }
    std::ifstream& in_;
    Opened& o_;
    std::string what_;
};

}  // namespace

void write_checkpoint(Pipeline& pipeline, const std::filesystem::path& file, const std::string& what, const std::string& build) {
    pipeline.drain();   // every record back: the guard has seen them all, and the plan's are saved
    if (const auto& bad = pipeline.instability())
        throw InputError(what + ": not written: the simulation went unstable at frame " + std::to_string(bad->frame));
    // The frames this pipeline ran must be known sound (a resumed one that has run none is as sound
    // as the checkpoint it was loaded from).
    const std::optional<std::uint64_t> sound = pipeline.poll();
    if (pipeline.frames() > pipeline.first_frame() && (!sound || *sound + 1 != pipeline.frames()))
        throw InputError(what + ": not written: the last frame is past a guard bound, and no later frame shows it was a spike");
    Saver saver;
    try {
        pipeline.persist(saver);
    } catch (const InputError& e) {
        throw InputError(what + ": not written: " + e.what());   // e.g. the paddle has moved the boundary
    }
    const scene::Scene& s = pipeline.scene();
    json entries = json::array();
    for (const auto& [name, bytes] : saver.entries) entries.push_back({{"name", name}, {"bytes", bytes.size()}});
    const json header = {{"format", kFormat},
                         {"build", build},
                         {"frame", pipeline.frames()},
                         {"time", pipeline.simulated_time()},
                         {"particles", pipeline.particle_count()},
                         {"scene",
                          {{"source", s.source},
                           {"origin", s.origin},
                           {"name", s.name},
                           {"spacing", s.spacing},
                           {"solver", scene::solver_name(s.sph.solver)}}},
                         {"entries", entries}};
    const std::string text = header.dump();
    const std::uint64_t length = text.size();
    std::vector<std::string_view> parts = {std::string_view(kMagic, sizeof kMagic),
                                           std::string_view(reinterpret_cast<const char*>(&kFormat), sizeof kFormat),
                                           std::string_view(reinterpret_cast<const char*>(&length), sizeof length), text};
    for (const auto& e : saver.entries) parts.emplace_back(e.second.data(), e.second.size());
    try {
        write_whole_file(file, parts, "", /*sync=*/true);
    } catch (const Error& e) {
        throw InputError(what + ": cannot write " + file.string() + ": " + e.what());
    }
}

void check_checkpoint_path(const std::filesystem::path& file, const std::string& what) {
    profile::check_writable(file, what);   // write_whole_file() writes "<file>.tmp" first, as it checks
}

CheckpointInfo read_checkpoint(const std::filesystem::path& file, const std::string& what, const std::string& build) {
    std::ifstream in;
    const Opened o = open_file(in, file, what);
    const json& sj = o.header.at("scene");
    CheckpointInfo info;
    try {
        const std::string wrote = o.header.at("build").get<std::string>();
        if (wrote != build)
            throw InputError(what + ": written by ranryu " + wrote + ", and this is " + build +
                             "; a checkpoint is read by the build that wrote it (its buffers' layouts are that build's)");
        scene::Scene s = scene::parse(sj.at("source").get<std::string>(), what + "'s scene");
        const float spacing = sj.at("spacing").get<float>();
        if (spacing != s.spacing) s = scene::with_spacing(s, spacing, what + "'s spacing");
        if (s.model == scene::Model::sph) s.sph.solver = scene::parse_solver(sj.at("solver").get<std::string>(), what + "'s solver");
        s.origin = sj.at("origin").get<std::string>();
        s.name = sj.at("name").get<std::string>();
        info.scene = std::move(s);
        info.frame = o.header.at("frame").get<std::uint64_t>();
        info.time = o.header.at("time").get<double>();
        info.particles = o.header.at("particles").get<std::size_t>();
    } catch (const json::exception& e) {
        throw InputError(what + ": malformed header: " + e.what());
    }
    return info;
}

void load_checkpoint(Pipeline& pipeline, const std::filesystem::path& file, const std::string& what) {
    std::ifstream in;
    Opened o = open_file(in, file, what);
    if (pipeline.frames() != 0) throw Error("load_checkpoint: the pipeline has already run frames");
    Loader loader(in, o, what);
    pipeline.persist(loader);
    loader.finish();
    // Every entry matched this run's (a file of another run fails above, by its entries' sizes), so a
    // count in the header that differs is damage.
    const std::uint64_t particles = o.header.at("particles").get<std::uint64_t>();
    if (particles != pipeline.particle_count())
        throw InputError(what + ": its header says " + std::to_string(particles) + " particles, and its scene has " +
                         std::to_string(pipeline.particle_count()) + " (a damaged file)");
}

}  // namespace ranryu::frame
