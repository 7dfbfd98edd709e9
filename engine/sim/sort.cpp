#include "sim/sort.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/error.h"
#include "gl/context.h"
#include "shared/bindings.h"

namespace ranryu::sim {
namespace {

static_assert(RANRYU_SORT_BITONIC_ITEMS_PER_THREAD >= 2, "a bitonic invocation handles ITEMS/2 comparators per step");
static_assert(RANRYU_SORT_RADIX_ITEMS_PER_THREAD >= 1);

constexpr unsigned kRadixBits = RANRYU_SORT_RADIX_BITS;
constexpr GLuint kRadixDigits = 1u << kRadixBits;
// Subgroup sizes the radix passes accept: a power of two that divides their 256 invocations into
// at most 16 subgroups (shared counters per subgroup and digit) and fits a 128-bit ballot.
constexpr GLint kMinSubgroup = 16, kMaxSubgroup = 128;


bool subgroups_disabled_by_env() {
    const char* v = std::getenv("RANRYU_NO_SUBGROUPS");
    return v && std::string_view(v) == "1";
}

std::string variant_defines(unsigned subgroup_size, bool emulated) {
    if (subgroup_size == 0) return {};
    return std::string(emulated ? "#define RANRYU_SUBGROUPS_EMULATED 1\n" : "#define RANRYU_SUBGROUPS 1\n") +
           "#define RANRYU_SUBGROUP_SIZE " + std::to_string(subgroup_size) + "\n";
}

GLuint groups(std::size_t items, std::size_t per_group) { return GLuint((items + per_group - 1) / per_group); }

void storage_barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); }

}  // namespace

unsigned KeySort::driver_subgroup_size() {
    if (!gl::has_extension("GL_KHR_shader_subgroup")) return 0;
    GLint size = 0, stages = 0, features = 0;
    glGetIntegerv(GL_SUBGROUP_SIZE_KHR, &size);
    glGetIntegerv(GL_SUBGROUP_SUPPORTED_STAGES_KHR, &stages);
    glGetIntegerv(GL_SUBGROUP_SUPPORTED_FEATURES_KHR, &features);
    const GLint needed = GL_SUBGROUP_FEATURE_BASIC_BIT_KHR | GL_SUBGROUP_FEATURE_VOTE_BIT_KHR |
                         GL_SUBGROUP_FEATURE_BALLOT_BIT_KHR | GL_SUBGROUP_FEATURE_ARITHMETIC_BIT_KHR;
    if (!(stages & GL_COMPUTE_SHADER_BIT) || (features & needed) != needed) return 0;
    if (size < kMinSubgroup || size > kMaxSubgroup || !std::has_single_bit(unsigned(size))) return 0;
    return unsigned(size);
}

unsigned KeySort::radix_passes(std::uint32_t max_key) {
    return (unsigned(std::bit_width(max_key)) + kRadixBits - 1) / kRadixBits;
}

KeySort::KeySort(const shader::FileSource& shaders, profile::GpuTimer& timer, std::size_t capacity,
                 SubgroupMode mode)
    : timer_(timer),
      count_pass_(timer.pass("sort.count")),
      scan_pass_(timer.pass("sort.scan")),
      scatter_pass_(timer.pass("sort.scatter")),
      bitonic_local_pass_(timer.pass("sort.bitonic_local")),
      bitonic_global_pass_(timer.pass("sort.bitonic_global")),
      bitonic_merge_local_pass_(timer.pass("sort.bitonic_merge_local")),
      capacity_(capacity) {
    const unsigned driver = driver_subgroup_size();
    switch (mode) {
        case SubgroupMode::automatic: subgroup_size_ = subgroups_disabled_by_env() ? 0 : driver; break;
        case SubgroupMode::shared_memory: subgroup_size_ = 0; break;
        case SubgroupMode::subgroups:
            if (!driver)
                throw Error("KeySort: SubgroupMode::subgroups, but the driver offers no usable "
                            "GL_KHR_shader_subgroup (basic, vote, ballot, arithmetic in compute, size 16..128)");
            subgroup_size_ = driver;
            break;
        case SubgroupMode::emulated:
            subgroup_size_ = driver ? driver : 32;
            emulated_ = true;
            break;
    }
    const std::string defines = variant_defines(subgroup_size_, emulated_);
    count_ = shader::Program::compute(shaders, "sim/sort/count_digits.comp", defines);
    scan_ = shader::Program::compute(shaders, "sim/sort/scan_counts.comp", defines);
    scan_serial_ = shader::Program::compute(shaders, "sim/sort/scan_counts.comp", defines + "#define RANRYU_SCAN_SERIAL 1\n");
    if (scan_serial_.local_size()[0] != kRadixDigits) throw Error("KeySort: the serial scan needs one invocation per digit");
    scatter_ = shader::Program::compute(shaders, "sim/sort/scatter_digits.comp", defines);
    bitonic_sort_local_ = shader::Program::compute(shaders, "sim/sort/bitonic_sort_local.comp");
    bitonic_merge_local_ = shader::Program::compute(shaders, "sim/sort/bitonic_merge_local.comp");
    bitonic_merge_global_ = shader::Program::compute(shaders, "sim/sort/bitonic_merge_global.comp");

    // Tiles come from the programs' declared sizes; count and scatter must agree on them.
    radix_tile_ = std::size_t(count_.local_size()[0]) * RANRYU_SORT_RADIX_ITEMS_PER_THREAD;
    if (std::size_t(scatter_.local_size()[0]) * RANRYU_SORT_RADIX_ITEMS_PER_THREAD != radix_tile_)
        throw Error("KeySort: count_digits and scatter_digits declare different workgroup sizes");
    bitonic_tile_ = std::size_t(bitonic_sort_local_.local_size()[0]) * RANRYU_SORT_BITONIC_ITEMS_PER_THREAD;
    if (std::size_t(bitonic_merge_local_.local_size()[0]) * RANRYU_SORT_BITONIC_ITEMS_PER_THREAD != bitonic_tile_ ||
        !std::has_single_bit(bitonic_tile_))
        throw Error("KeySort: the local bitonic passes must share one power-of-two tile");

    GLint max_groups = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups);
    max_groups_ = GLuint(max_groups);
    // One workgroup per tile; bitonic indices up to bit_ceil(capacity) must fit a uint.
    if (std::max(groups(capacity, radix_tile_), groups(capacity, bitonic_tile_)) > max_groups_ ||
        capacity > (std::size_t(1) << 30))
        throw Error("KeySort: capacity " + std::to_string(capacity) + " needs more workgroups than the driver's " +
                    std::to_string(max_groups) + " per dispatch");

    const std::size_t bytes = pair_array_bytes(capacity);
    keys_ = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "sort.keys");
    values_ = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "sort.values");
    keys_alt_ = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "sort.keys_alt");
    values_alt_ = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "sort.values_alt");
    histogram_ = gl::Buffer(histogram_bytes(capacity, radix_tile_), GL_DYNAMIC_COPY, nullptr, "sort.histogram");
}

std::size_t KeySort::pair_array_bytes(std::size_t capacity) {
    return std::max<std::size_t>(capacity, 1) * sizeof(std::uint32_t);
}
// total[digit], then count[digit][tile] (glsl/sim/sort/radix.glsl).
std::size_t KeySort::histogram_bytes(std::size_t capacity, std::size_t radix_tile) {
    const std::size_t tiles = std::max<std::size_t>(groups(capacity, radix_tile), 1);
    return (kRadixDigits + kRadixDigits * tiles) * sizeof(std::uint32_t);
}
std::size_t KeySort::bytes_for(std::size_t capacity) {
    // radix.glsl's RADIX_GROUP is RADIX_DIGITS: the tile the constructor reads from the programs.
    return 4 * pair_array_bytes(capacity) + histogram_bytes(capacity, kRadixDigits * RANRYU_SORT_RADIX_ITEMS_PER_THREAD);
}

void KeySort::sort(SortMethod method, std::size_t count, std::uint32_t max_key) {
    if (count > capacity_)
        throw Error("KeySort::sort: " + std::to_string(count) + " pairs exceed the capacity of " +
                    std::to_string(capacity_));
    result_in_alt_ = false;
    storage_barrier();   // the caller's hash pass wrote keys()/values(); also covers the early returns
    if (count < 2) return;
    switch (method) {
        case SortMethod::radix: sort_radix(count, max_key); break;
        case SortMethod::bitonic: sort_bitonic(count); break;
    }
}

// Per digit, low to high: count -> scan -> scatter, reading one buffer pair and writing the other.
void KeySort::sort_radix(std::size_t count, std::uint32_t max_key) {
    const unsigned bits = unsigned(std::bit_width(max_key));
    if (bits == 0) return;   // every key is 0: the input is sorted, and stably
    const GLuint tiles = groups(count, radix_tile_);
    const auto n = GLuint(count);
    glProgramUniform1ui(count_.id(), RANRYU_LOC_COUNT, n);
    glProgramUniform1ui(scan_.id(), RANRYU_LOC_COUNT, n);
    glProgramUniform1ui(scan_serial_.id(), RANRYU_LOC_COUNT, n);
    glProgramUniform1ui(scatter_.id(), RANRYU_LOC_COUNT, n);
    bool alt = false;
    for (unsigned shift = 0; shift < bits; shift += kRadixBits) {
        const unsigned digit_bits = std::min(kRadixBits, bits - shift);
        for (const shader::Program* p : {&count_, &scatter_}) {
            glProgramUniform1ui(p->id(), RANRYU_LOC_SHIFT, shift);
            glProgramUniform1ui(p->id(), RANRYU_LOC_AUX, digit_bits);
        }
        const shader::StorageSet buffers{{"Keys", alt ? &keys_alt_ : &keys_},
                                         {"KeysIn", alt ? &keys_alt_ : &keys_},
                                         {"ValuesIn", alt ? &values_alt_ : &values_},
                                         {"KeysOut", alt ? &keys_ : &keys_alt_},
                                         {"ValuesOut", alt ? &values_ : &values_alt_},
                                         {"Histogram", &histogram_}};
        {
            auto pass = timer_.scope(count_pass_);
            count_.bind(buffers).use();
            glDispatchCompute(tiles, 1, 1);
        }
        storage_barrier();
        {
            auto pass = timer_.scope(scan_pass_);
            if (tiles <= kSerialScanTiles) {
                scan_serial_.bind(buffers).use();
                glDispatchCompute(1, 1, 1);
            } else {
                scan_.bind(buffers).use();
                glDispatchCompute(1u << digit_bits, 1, 1);   // digits this pass can hold; see scan_counts.comp
            }
        }
        storage_barrier();
        {
            auto pass = timer_.scope(scatter_pass_);
            scatter_.bind(buffers).use();
            glDispatchCompute(tiles, 1, 1);
        }
        storage_barrier();
        alt = !alt;
    }
    result_in_alt_ = alt;
}

// Local sort of every tile, then for each stage k beyond the tile: global steps j = k/2 .. tile,
// then the strides below the tile in one local dispatch.
void KeySort::sort_bitonic(std::size_t count) {
    const auto n = GLuint(count);
    const std::size_t padded = std::bit_ceil(count);
    const GLuint tiles = groups(count, bitonic_tile_);
    const GLuint global_groups =
        std::min(groups(std::min(padded / 2, count), bitonic_merge_global_.local_size()[0]), max_groups_);
    glProgramUniform1ui(bitonic_sort_local_.id(), RANRYU_LOC_COUNT, n);
    glProgramUniform1ui(bitonic_merge_local_.id(), RANRYU_LOC_COUNT, n);
    glProgramUniform1ui(bitonic_merge_global_.id(), RANRYU_LOC_COUNT, n);
    const shader::StorageSet buffers{{"Keys", &keys_}, {"Values", &values_}};
    {
        auto pass = timer_.scope(bitonic_local_pass_);
        bitonic_sort_local_.bind(buffers).use();
        glDispatchCompute(tiles, 1, 1);
    }
    storage_barrier();
    for (std::size_t k = 2 * bitonic_tile_; k <= padded; k *= 2) {
        for (std::size_t j = k / 2; j >= bitonic_tile_; j /= 2) {
            glProgramUniform2ui(bitonic_merge_global_.id(), RANRYU_LOC_STAGE, GLuint(k), GLuint(j));
            {
                auto pass = timer_.scope(bitonic_global_pass_);
                bitonic_merge_global_.bind(buffers).use();
                glDispatchCompute(global_groups, 1, 1);
            }
            storage_barrier();
        }
        glProgramUniform2ui(bitonic_merge_local_.id(), RANRYU_LOC_STAGE, GLuint(k), 0u);
        {
            auto pass = timer_.scope(bitonic_merge_local_pass_);
            bitonic_merge_local_.bind(buffers).use();
            glDispatchCompute(tiles, 1, 1);
        }
        storage_barrier();
    }
}

}  // namespace ranryu::sim
