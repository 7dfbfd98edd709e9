// The scene parser fed random mutations of the bundled scenes, in process: whatever the bytes, parse()
// returns a scene or throws ranryu::InputError naming the input; never another exception (which the
// binary would report as a failure, exit 1), a crash or a hang. A fixed seed keeps it repeatable;
// under scripts/sanitize.sh it runs with AddressSanitizer and UBSan. tests/fuzz/scene_fuzzer.cpp is
// the same check as a libFuzzer target, for longer runs with clang.
#include <catch2/catch.hpp>

#include <random>
#include <string>
#include <vector>

#include "core/embedded.h"
#include "core/error.h"
#include "scene/scene.h"

namespace ranryu::scene {
extern const EmbeddedFile kEmbeddedFiles[];
extern const unsigned kEmbeddedFileCount;
}  // namespace ranryu::scene

using namespace ranryu::scene;

namespace {

// Tokens that reach the parser's edges: bounds, types, nesting, encodings.
const std::vector<std::string> kTokens = {
    "0", "-0", "-1", "1e999", "-1e999", "1e-999", "1e308", "18446744073709551616", "2147483648", "0.5", "NaN", "Infinity",
    "null", "true", "false", "\"\"", "\"sph\"", "\"dfsph\"", "[]", "{}", "[0,0,0]", "[1,2]", "[[[[[[[[", "]]]]", "{\"a\":",
    "\"\xff\"", "\"\\u0000\"", "\"\\ud800\"", ",", ":", "\"", "\\", "\xef\xbb\xbf", "\"radius\": 0.1", "\"center\": [0,0,0]",
    "\"min\": [1,1,1]", "\"max\": [0,0,0]", "\"levels\": 3", "\"amplitude\": 5", "\"octaves\": [6, 4]",
};

std::string mutate(std::string s, std::mt19937& rng) {
    const auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n == 0 ? 0 : n - 1)(rng); };
    const int edits = 1 + int(pick(4));
    for (int e = 0; e < edits; ++e) {
        const std::size_t at = pick(s.size() + 1);
        switch (pick(6)) {
            case 0: if (at < s.size()) s[at] = char(pick(256)); break;                       // flip a byte
            case 1: s.insert(at, kTokens[pick(kTokens.size())]); break;                       // insert a token
            case 2: s.erase(at, pick(16)); break;                                              // delete a run
            case 3: s.resize(at); break;                                                       // truncate
            case 4: {                                                                          // replace a number
                const std::size_t d = s.find_first_of("0123456789", at);
                if (d != std::string::npos) s.replace(d, s.find_first_not_of("0123456789.e-", d) - d, kTokens[pick(12)]);
                break;
            }
            default: {                                                                         // copy a slice elsewhere
                const std::size_t from = pick(s.size()), n = pick(64);
                s.insert(at, s.substr(from, n));
            }
        }
    }
    return s;
}

}  // namespace

TEST_CASE("scene parser: random mutations of the bundled scenes give a scene or an InputError naming the input", "[scene][fuzz]") {
    std::vector<std::string> seeds;
    for (unsigned i = 0; i < kEmbeddedFileCount; ++i)
        if (kEmbeddedFiles[i].path.starts_with("scenes/")) seeds.emplace_back(kEmbeddedFiles[i].text);
    REQUIRE(seeds.size() >= 5);
    std::mt19937 rng(20261125);
    int refused = 0, accepted = 0;
    for (int i = 0; i < 4000; ++i) {
        const std::string text = mutate(seeds[std::size_t(i) % seeds.size()], rng);
        try {
            (void)parse(text, "mutant.json");
            ++accepted;
        } catch (const ranryu::InputError& e) {
            const std::string what = e.what();
            if (what.find("mutant.json") == std::string::npos) FAIL("the message does not name the input: " << what);
            ++refused;
        } catch (const std::exception& e) {
            FAIL("parse threw " << typeid(e).name() << ", not InputError: " << e.what() << "\non:\n" << text);
        }
    }
    INFO(accepted << " accepted, " << refused << " refused");
    CHECK(refused > 1000);   // the mutations reach the checks
    CHECK(accepted > 50);    // and some leave a valid scene
}
