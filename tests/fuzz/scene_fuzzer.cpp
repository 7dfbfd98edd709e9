// libFuzzer target for the scene parser: whatever the bytes, parse() returns a scene or throws
// ranryu::InputError; any other exception, a crash or a sanitizer report is a finding. Needs clang:
//   CXX=clang++ cmake -S . -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=Debug -DRANRYU_FUZZ=ON
//   cmake --build build/fuzz --target ranryu_scene_fuzzer
//   mkdir -p /tmp/corpus && build/fuzz/tests/ranryu_scene_fuzzer /tmp/corpus media/scenes tests/data/scenes -max_total_time=600
// Not in CI (Debian's CI image has no clang); tests/unit/scene_fuzz_test.cpp runs the same check on
// seeded random mutations in every suite run, and under the sanitizers.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        (void)ranryu::scene::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    } catch (const ranryu::InputError&) {
    }
    return 0;
}
