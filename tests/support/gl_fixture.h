#pragma once
// Shared by the GL tests: one headless debug context per test process (llvmpipe in CI, the GPU
// where there is one), GL errors checked after each case, and fresh random inputs whose seed is
// printed on failure (RANRYU_TEST_SEED=N repeats a run).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <random>
#include <string>

#include "gl/context.h"

namespace ranryu::test {

inline gl::HeadlessContext& context() {
    static gl::HeadlessContext ctx(/*debug=*/true);
    static const bool installed = (gl::install_debug_callback(), true);
    (void)installed;
    return ctx;
}

// Fails the current case if the driver reported a GL error since the last check.
inline void require_no_gl_errors() {
    const auto errors = gl::take_gl_errors();
    std::string all;
    for (const auto& e : errors) all += e + "\n";
    INFO(all);
    REQUIRE(errors.empty());
}

// A generator seeded afresh each run (or from RANRYU_TEST_SEED); the seed is logged with INFO by
// the caller through seed().
class Random {
public:
    Random() : seed_(pick()), engine_(seed_) {}
    unsigned seed() const { return seed_; }
    std::mt19937& engine() { return engine_; }
    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(engine_); }
    unsigned below(unsigned n) { return std::uniform_int_distribution<unsigned>(0, n - 1)(engine_); }

private:
    static unsigned pick() {
        if (const char* s = std::getenv("RANRYU_TEST_SEED")) return unsigned(std::strtoul(s, nullptr, 10));
        return std::random_device{}();
    }
    unsigned seed_;
    std::mt19937 engine_;
};

}  // namespace ranryu::test
