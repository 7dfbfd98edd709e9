#pragma once
// GPU sort of (uint key, uint value) pairs: the "sort" step of the grid neighbour search
// (docs/METHOD.md §1: hash -> sort (hash, index) -> cell ranges).
//
//   radix    LSD radix sort, 8-bit digits, stable (Satish, Harris & Garland, IPDPS 2009). Per digit:
//            count_digits -> scan_counts -> scatter_digits (glsl/sim/sort/), passes "sort.count",
//            "sort.scan", "sort.scatter". Only the ceil(bit_width(max_key) / 8) low digits are
//            sorted: a 64^3 grid (18-bit keys) takes 3 passes, full 32-bit keys 4.
//   bitonic  Batcher's bitonic network (AFIPS 1968) on (key, value), in place, padded in the kernel
//            to the next power of two; passes "sort.bitonic_local", "sort.bitonic_global" and "sort.bitonic_merge_local".
//            O(n log^2 n): the simple reference method.
//
// Both give the same order when value = the pair's original index (the neighbour search's case):
// radix because it is stable, bitonic because it sorts by (key, value).
//
// The radix ranking uses GL_KHR_shader_subgroup (ballot, vote, arithmetic) where the driver offers
// it for compute shaders, and shared memory only otherwise; both orders are identical.
// RANRYU_NO_SUBGROUPS=1 in the environment, or SubgroupMode::shared_memory, forces the latter.
//
// Frame-path guarantees: sort() allocates nothing, compiles nothing, reads nothing back and never
// waits; every dispatch is timed and labelled through the GpuTimer, so sort() runs between
// timer.begin_frame() and timer.end_frame().
#include <cstddef>
#include <cstdint>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"

namespace ranryu::sim {

enum class SortMethod { radix, bitonic };

// Which ranking the radix passes compile.
enum class SubgroupMode {
    automatic,      // the driver's subgroups when it has them and RANRYU_NO_SUBGROUPS is not 1
    shared_memory,  // shared memory only (the fallback; any GL 4.3 driver)
    subgroups,      // the driver's subgroups; the constructor throws when it has none
    emulated,       // tests: the subgroup algorithm on a shared-memory emulation of the subgroup
                    // built-ins (any driver; slow). Checks the subgroup code where no driver has them.
};

class KeySort {
public:
    // Builds every program and allocates every buffer for up to `capacity` pairs. Throws
    // ranryu::Error when capacity exceeds what one dispatch can cover or when `mode` asks for
    // subgroups the driver lacks. Needs a current GL 4.3 context.
    KeySort(const shader::FileSource& shaders, profile::GpuTimer& timer, std::size_t capacity,
            SubgroupMode mode = SubgroupMode::automatic);
    // Device memory the constructor allocates for `capacity` pairs (frame/memory.h).
    static std::size_t bytes_for(std::size_t capacity);

    // The input: the caller writes `count` keys and values here, e.g. with the buffers bound at
    // the storage blocks Keys, Values (uint[capacity] each), before sort().
    // sort() issues the memory barrier that makes earlier shader writes to them visible.
    gl::Buffer& keys() { return keys_; }
    gl::Buffer& values() { return values_; }

    // Sorts the first `count` pairs by key; every key must be <= max_key (larger keys are sorted
    // by their low bit_width(max_key) bits only). count <= capacity(), else ranryu::Error.
    // Radix is stable; bitonic orders equal keys by value. Afterwards sorted_keys()/sorted_values()
    // hold the result: keys()/values() or the alternate buffers (radix ping-pongs once per digit).
    // The other pair of buffers, and pairs past `count`, hold garbage. Ends with
    // glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT), so later passes may read the result as SSBOs.
    void sort(SortMethod method, std::size_t count, std::uint32_t max_key);

    const gl::Buffer& sorted_keys() const { return result_in_alt_ ? keys_alt_ : keys_; }
    const gl::Buffer& sorted_values() const { return result_in_alt_ ? values_alt_ : values_; }

    std::size_t capacity() const { return capacity_; }
    // Pairs per workgroup: radix tile (count/scatter) and bitonic shared-memory tile.
    std::size_t radix_tile() const { return radix_tile_; }
    std::size_t bitonic_tile() const { return bitonic_tile_; }
    // The subgroup size the radix passes were compiled for; 0 on the shared-memory path.
    unsigned subgroup_size() const { return subgroup_size_; }
    bool emulated_subgroups() const { return emulated_; }
    // Radix digit passes for keys up to max_key: ceil(bit_width(max_key) / RANRYU_SORT_RADIX_BITS).
    static unsigned radix_passes(std::uint32_t max_key);

    // The driver's subgroup size when it offers GL_KHR_shader_subgroup with basic, vote, ballot and
    // arithmetic operations in compute shaders at a size the radix passes support; 0 otherwise.
    static unsigned driver_subgroup_size();

private:
    void sort_radix(std::size_t count, std::uint32_t max_key);
    void sort_bitonic(std::size_t count);

    profile::GpuTimer& timer_;
    profile::PassId count_pass_, scan_pass_, scatter_pass_, bitonic_local_pass_, bitonic_global_pass_, bitonic_merge_local_pass_;
    std::size_t capacity_ = 0;
    unsigned subgroup_size_ = 0;
    bool emulated_ = false;
    // Up to this many tiles the scan runs as one workgroup, an invocation per digit (scan_counts.comp).
    static constexpr GLuint kSerialScanTiles = 32;
    shader::Program count_, scan_, scan_serial_, scatter_;
    shader::Program bitonic_sort_local_, bitonic_merge_local_, bitonic_merge_global_;
    std::size_t radix_tile_ = 0, bitonic_tile_ = 0;
    GLuint max_groups_ = 0;
    static std::size_t pair_array_bytes(std::size_t capacity);
    static std::size_t histogram_bytes(std::size_t capacity, std::size_t radix_tile);
    gl::Buffer keys_, values_, keys_alt_, values_alt_, histogram_;
    bool result_in_alt_ = false;
};

}  // namespace ranryu::sim
