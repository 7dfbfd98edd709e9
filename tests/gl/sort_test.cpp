// engine/sim/sort.*: every method and radix variant against std::stable_sort on the CPU, keys and
// values compared exactly, with value = original index (so a stable order is the only right one).
#include "support/gl_fixture.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "profile/gpu_timer.h"
#include "profile/report.h"
#include "shared/bindings.h"
#include "shader/source.h"
#include "sim/sort.h"

namespace {

using ranryu::sim::KeySort;
using ranryu::sim::SortMethod;
using ranryu::sim::SubgroupMode;
using Keys = std::vector<std::uint32_t>;

constexpr std::size_t kCapacity = 300'007;

// One sorter per radix variant, built once per process (shader compiles are slow on llvmpipe).
struct Sorters {
    Sorters() {
        ranryu::test::context();
        const auto shaders = ranryu::shader::FileSource::embedded();
        timer = std::make_unique<ranryu::profile::GpuTimer>();
        shared = std::make_unique<KeySort>(shaders, *timer, kCapacity, SubgroupMode::shared_memory);
        emulated = std::make_unique<KeySort>(shaders, *timer, kCapacity, SubgroupMode::emulated);
        if (KeySort::driver_subgroup_size() != 0)
            driver = std::make_unique<KeySort>(shaders, *timer, kCapacity, SubgroupMode::subgroups);
    }
    std::unique_ptr<ranryu::profile::GpuTimer> timer;
    std::unique_ptr<KeySort> shared, emulated, driver;
};

Sorters& sorters() {
    static Sorters s;
    return s;
}

struct Variant {
    std::string name;
    KeySort* sorter;
    SortMethod method;
};

// The variants every check runs. `emulated`: also the radix on emulated subgroups (slow on llvmpipe:
// each emulated ballot is three workgroup barriers).
std::vector<Variant> variants(bool emulated = true) {
    Sorters& s = sorters();
    std::vector<Variant> v{{"radix, shared memory", s.shared.get(), SortMethod::radix},
                           {"bitonic", s.shared.get(), SortMethod::bitonic}};
    if (emulated) v.push_back({"radix, emulated subgroups", s.emulated.get(), SortMethod::radix});
    if (s.driver)
        v.push_back({"radix, driver subgroups (size " + std::to_string(s.driver->subgroup_size()) + ")",
                     s.driver.get(), SortMethod::radix});
    return v;
}

// Runs one sort on the GPU and returns (keys, values) of the result.
std::pair<Keys, Keys> gpu_sort(const Variant& v, const Keys& keys, const Keys& values, std::uint32_t max_key) {
    KeySort& s = *v.sorter;
    s.keys().upload(keys.data(), keys.size() * sizeof(std::uint32_t));
    s.values().upload(values.data(), values.size() * sizeof(std::uint32_t));
    auto& timer = *sorters().timer;
    timer.begin_frame();
    s.sort(v.method, keys.size(), max_key);
    timer.end_frame();
    return {s.sorted_keys().read<std::uint32_t>(keys.size()), s.sorted_values().read<std::uint32_t>(keys.size())};
}

// Index of the first difference, or -1.
long first_difference(const Keys& a, const Keys& b) {
    const auto m = std::mismatch(a.begin(), a.end(), b.begin(), b.end());
    return m.first == a.end() && m.second == b.end() ? -1 : long(m.first - a.begin());
}

// Sorts (key, original index) pairs with every variant and compares with std::stable_sort.
void check_sorts(const Keys& keys, std::uint32_t max_key, bool emulated = true) {
    Keys index(keys.size());
    std::iota(index.begin(), index.end(), 0u);
    Keys want_values = index;
    std::stable_sort(want_values.begin(), want_values.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
    Keys want_keys(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) want_keys[i] = keys[want_values[i]];

    for (const Variant& v : variants(emulated)) {
        INFO(v.name << ", " << keys.size() << " pairs, max_key " << max_key);
        const auto [got_keys, got_values] = gpu_sort(v, keys, index, max_key);
        const long k = first_difference(got_keys, want_keys);
        const long i = first_difference(got_values, want_values);
        std::string where;
        if (k >= 0) where += "first wrong key at " + std::to_string(k) + ": " + std::to_string(got_keys[std::size_t(k)]) +
                             " instead of " + std::to_string(want_keys[std::size_t(k)]) + "\n";
        if (i >= 0) where += "first wrong value at " + std::to_string(i) + ": " + std::to_string(got_values[std::size_t(i)]) +
                             " instead of " + std::to_string(want_values[std::size_t(i)]);
        INFO(where);
        CHECK(k == -1);
        CHECK(i == -1);
    }
    ranryu::test::require_no_gl_errors();
}

Keys random_keys(ranryu::test::Random& rng, std::size_t n, std::uint32_t max_key) {
    std::uniform_int_distribution<std::uint32_t> pick(0, max_key);
    Keys k(n);
    for (auto& x : k) x = pick(rng.engine());
    return k;
}

}  // namespace

TEST_CASE("sort: tiles come from the programs and radix passes from max_key", "[sort]") {
    const KeySort& s = *sorters().shared;
    INFO(ranryu::test::context().info().line());
    INFO("driver subgroup size " << KeySort::driver_subgroup_size());
    CHECK(s.radix_tile() % RANRYU_SORT_RADIX_ITEMS_PER_THREAD == 0);
    CHECK(s.radix_tile() > RANRYU_SORT_RADIX_ITEMS_PER_THREAD);
    CHECK(s.radix_tile() < 65536);   // scatter_digits' 16-bit in-tile counters
    CHECK(s.bitonic_tile() > 1);
    CHECK((s.bitonic_tile() & (s.bitonic_tile() - 1)) == 0);
    CHECK(s.subgroup_size() == 0);
    CHECK(sorters().emulated->emulated_subgroups());
    CHECK(KeySort::radix_passes(0) == 0);
    CHECK(KeySort::radix_passes(1) == 1);
    CHECK(KeySort::radix_passes(255) == 1);
    CHECK(KeySort::radix_passes(256) == 2);
    CHECK(KeySort::radix_passes(64 * 64 * 64 - 1) == 3);
    CHECK(KeySort::radix_passes(0xFFFFFFFFu) == 4);
    // RANRYU_NO_SUBGROUPS=1 turns the automatic choice to shared memory.
    ::setenv("RANRYU_NO_SUBGROUPS", "1", 1);
    ranryu::profile::GpuTimer timer;
    const KeySort forced(ranryu::shader::FileSource::embedded(), timer, 16);
    ::unsetenv("RANRYU_NO_SUBGROUPS");
    CHECK(forced.subgroup_size() == 0);
    CHECK_FALSE(forced.emulated_subgroups());
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("sort: sizes 0 1 and 2", "[sort]") {
    check_sorts({}, 0xFFFFFFFFu);
    check_sorts({7}, 7);
    check_sorts({5, 3}, 5);
    check_sorts({3, 5}, 0xFFFFFFFFu);
    check_sorts({4, 4}, 4);
    check_sorts({0xFFFFFFFFu, 0}, 0xFFFFFFFFu);
}

TEST_CASE("sort: 1000 random 32-bit keys", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    check_sorts(random_keys(rng, 1000, 0xFFFFFFFFu), 0xFFFFFFFFu);
}

TEST_CASE("sort: sizes at the tile edges", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const KeySort& s = *sorters().shared;
    for (std::size_t n : {s.radix_tile() - 1, s.radix_tile(), s.radix_tile() + 1, s.bitonic_tile() + 1,
                          2 * s.bitonic_tile() + 3, 3 * s.radix_tile()})
        check_sorts(random_keys(rng, n, 50'000), 50'000);
}

TEST_CASE("sort: 70001 random keys (more than 65536)", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    check_sorts(random_keys(rng, 70'001, 0xFFFFFFFFu), 0xFFFFFFFFu);
}

TEST_CASE("sort: 300007 cell keys of a 64x64x64 grid (3 radix passes)", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    check_sorts(random_keys(rng, kCapacity, 64 * 64 * 64 - 1), 64 * 64 * 64 - 1, /*emulated=*/false);
}

TEST_CASE("sort: all keys equal", "[sort]") {
    check_sorts(Keys(20'000, 12'345u), 12'345u);
    check_sorts(Keys(20'000, 12'345u), 0xFFFFFFFFu);
    check_sorts(Keys(5'000, 0u), 0u);   // max_key 0: no radix pass at all
}

TEST_CASE("sort: keys at the top of the range", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Keys keys = random_keys(rng, 20'000, 1000);
    for (auto& k : keys) k = 0xFFFFFFFFu - k;
    keys[rng.below(unsigned(keys.size()))] = 0xFFFFFFFFu;
    keys[rng.below(unsigned(keys.size()))] = 0u;
    check_sorts(keys, 0xFFFFFFFFu);
    // Near the top of a smaller range: every key's top digit is max_key's.
    Keys near(20'000);
    for (auto& k : near) k = 0x00FFFFFFu - rng.below(300);
    check_sorts(near, 0x00FFFFFFu);
}

TEST_CASE("sort: already sorted and reversed", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Keys keys = random_keys(rng, 30'000, 5'000);   // with repeats
    std::sort(keys.begin(), keys.end());
    check_sorts(keys, 5'000);
    std::reverse(keys.begin(), keys.end());
    check_sorts(keys, 5'000);
}

TEST_CASE("sort: random keys below a small max_key", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    check_sorts(random_keys(rng, 70'001, 1023), 1023);   // 2 passes, the second of 2 bits
    check_sorts(random_keys(rng, 10'000, 255), 255);     // 1 pass
    check_sorts(random_keys(rng, 10'000, 256), 256);     // 2 passes, the second of 1 bit
    check_sorts(random_keys(rng, 10'000, 1), 1);         // 1 pass of 1 bit
}

TEST_CASE("sort: values travel with their keys whatever they are", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const Keys keys = random_keys(rng, 9'000, 300);
    const Keys values = random_keys(rng, keys.size(), 0xFFFFFFFFu);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) pairs[i] = {keys[i], values[i]};
    auto stable = pairs;
    std::stable_sort(stable.begin(), stable.end(), [](auto a, auto b) { return a.first < b.first; });
    auto by_pair = pairs;
    std::sort(by_pair.begin(), by_pair.end());
    for (const Variant& v : variants()) {
        INFO(v.name);
        const auto [got_keys, got_values] = gpu_sort(v, keys, values, 300);
        const auto& want = v.method == SortMethod::radix ? stable : by_pair;
        long wrong = -1;
        for (std::size_t i = 0; i < want.size() && wrong < 0; ++i)
            if (got_keys[i] != want[i].first || got_values[i] != want[i].second) wrong = long(i);
        CHECK(wrong == -1);
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("sort: a sorter can be reused with fewer pairs and another method", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    check_sorts(random_keys(rng, 50'000, 0xFFFFFFFFu), 0xFFFFFFFFu, /*emulated=*/false);
    check_sorts(random_keys(rng, 3'001, 100), 100);
    KeySort& s = *sorters().shared;
    CHECK_THROWS(s.sort(SortMethod::radix, s.capacity() + 1, 1));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("sort: every dispatch is a timed pass", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    auto& timer = *sorters().timer;
    KeySort& s = *sorters().shared;
    const Keys keys = random_keys(rng, 5'000, 0xFFFFu);
    const Variant radix{"radix", &s, SortMethod::radix};
    timer.drain();
    timer.reset_samples();
    gpu_sort(radix, keys, keys, 0xFFFFu);
    timer.drain();
    for (const auto& p : timer.passes()) {
        INFO(p.name);
        if (p.name == "sort.count" || p.name == "sort.scan" || p.name == "sort.scatter") {
            REQUIRE(p.calls.size() == 1);
            CHECK(p.calls[0] == int(KeySort::radix_passes(0xFFFFu)));
        }
    }
    ranryu::test::require_no_gl_errors();
}

// scan_counts walks a digit's row in chunks with a carry; sorts that fit this test's capacity never
// need a second chunk, so the pass runs here alone on the histogram of 16M keys (8192 tiles).
TEST_CASE("sort: scan_counts carries across chunks for 16M keys", "[sort]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const auto shaders = ranryu::shader::FileSource::embedded();
    const std::size_t tile = sorters().shared->radix_tile();
    const std::size_t keys = std::size_t(16) << 20;
    const std::size_t tiles = (keys + tile - 1) / tile;
    constexpr std::size_t digits = 1u << RANRYU_SORT_RADIX_BITS;
    Keys counts(digits + digits * tiles);
    for (std::size_t i = digits; i < counts.size(); ++i) counts[i] = rng.below(unsigned(tile / 64));
    Keys want(counts.size());
    for (std::size_t d = 0; d < digits; ++d) {
        std::uint32_t sum = 0;
        for (std::size_t t = 0; t < tiles; ++t) {
            want[digits + d * tiles + t] = sum;
            sum += counts[digits + d * tiles + t];
        }
        want[d] = sum;
    }
    const std::pair<const char*, const char*> variants[] = {
        {"shared memory", ""},
        {"emulated subgroups", "#define RANRYU_SUBGROUPS_EMULATED 1\n#define RANRYU_SUBGROUP_SIZE 32\n"}};
    for (const auto& [name, defines] : variants) {
        INFO(name);
        const auto scan = ranryu::shader::Program::compute(shaders, "sim/sort/scan_counts.comp", defines);
        auto histogram = ranryu::gl::Buffer::from<std::uint32_t>(counts, GL_DYNAMIC_COPY, "test.histogram");
        glProgramUniform1ui(scan.id(), RANRYU_LOC_COUNT, GLuint(keys));
        scan.bind({{"Histogram", &histogram}}).use();
        glDispatchCompute(digits, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const Keys got = histogram.read<std::uint32_t>(counts.size());
        CHECK(first_difference(got, want) == -1);
    }
    ranryu::test::require_no_gl_errors();
}

// Hidden (not run by default or by ctest): GPU time per pass of radix (each ranking variant) and
// bitonic on the device, printed as the profile table. For the H100:
//     ranryu_gl_tests "[sort-bench]"        RANRYU_SORT_BENCH_N (default 1048576),
//                                           RANRYU_SORT_BENCH_FRAMES (default 50)
// Every frame restores the unsorted input with a GPU copy outside the timed passes, so each sort
// starts from the same random keys; the last result is checked against std::stable_sort.
TEST_CASE("sort: benchmark", "[.][sort-bench]") {
    const auto env = [](const char* name, std::size_t fallback) {
        const char* v = std::getenv(name);
        return v ? std::size_t(std::strtoull(v, nullptr, 10)) : fallback;
    };
    const std::size_t n = env("RANRYU_SORT_BENCH_N", std::size_t(1) << 20);
    const int frames = int(env("RANRYU_SORT_BENCH_FRAMES", 50)), warmup = 5;
    const auto& info = ranryu::test::context().info();
    const auto shaders = ranryu::shader::FileSource::embedded();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    struct Bench {
        std::string name;
        SubgroupMode mode;
        SortMethod method;
    };
    std::vector<Bench> benches{{"radix, shared memory", SubgroupMode::shared_memory, SortMethod::radix}};
    if (KeySort::driver_subgroup_size() != 0)
        benches.push_back({"radix, subgroups", SubgroupMode::subgroups, SortMethod::radix});
    benches.push_back({"bitonic", SubgroupMode::shared_memory, SortMethod::bitonic});
    for (const std::uint32_t max_key : {64u * 64u * 64u - 1u, 0xFFFFFFFFu}) {
        const Keys keys = random_keys(rng, n, max_key);
        Keys index(n);
        std::iota(index.begin(), index.end(), 0u);
        Keys want = index;
        std::stable_sort(want.begin(), want.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
        const auto input_keys = ranryu::gl::Buffer::from<std::uint32_t>(keys, GL_STATIC_COPY, "bench.keys");
        const auto input_values = ranryu::gl::Buffer::from<std::uint32_t>(index, GL_STATIC_COPY, "bench.values");
        for (const Bench& b : benches) {
            ranryu::profile::GpuTimer timer;
            KeySort s(shaders, timer, n, b.mode);
            for (int f = 0; f < warmup + frames; ++f) {
                if (f == warmup) {
                    timer.drain();
                    timer.reset_samples();
                }
                for (auto [from, to] : {std::pair{&input_keys, &s.keys()}, std::pair{&input_values, &s.values()}}) {
                    glBindBuffer(GL_COPY_READ_BUFFER, from->id());
                    glBindBuffer(GL_COPY_WRITE_BUFFER, to->id());
                    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(n * 4));
                }
                timer.begin_frame();
                s.sort(b.method, n, max_key);
                timer.end_frame();
            }
            timer.drain();
            ranryu::profile::RunInfo run;
            run.renderer = info.renderer;
            run.driver = info.version;
            run.platform = info.platform;
            run.scene = b.name + ", " + std::to_string(n) + " pairs, max_key " + std::to_string(max_key) +
                        (s.subgroup_size() ? ", subgroup size " + std::to_string(s.subgroup_size()) : "");
            run.particles = n;
            run.frames = frames;
            run.warmup = warmup;
            std::cout << run.scene << "\n" << ranryu::profile::table(ranryu::profile::summarize(timer, run)) << "\n";
            INFO(run.scene);
            CHECK(first_difference(s.sorted_values().read<std::uint32_t>(n), want) == -1);
        }
    }
    ranryu::test::require_no_gl_errors();
}
