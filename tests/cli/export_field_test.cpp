// `ranryu export-field` end to end: a valid .npy v1.0 (magic, version, '<f4', C order, shape
// (N, N, N, 3)) of finite, non-zero values; refusal to overwrite without --force (exit 2, file
// unchanged); --force replaces it; bad --size / --octaves / missing --out exit 2 with one line naming
// the option, and nothing is written.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>

#include "cli/run_helper.h"

using namespace ranryu::test;

namespace {

struct Npy {
    int major = 0, minor = 0;
    std::string dict;
    std::size_t data_offset = 0;
};

Npy parse_npy(const std::string& bytes) {
    Npy n;
    REQUIRE(bytes.size() >= 10);
    REQUIRE(bytes.compare(0, 6, "\x93NUMPY") == 0);
    n.major = static_cast<unsigned char>(bytes[6]);
    n.minor = static_cast<unsigned char>(bytes[7]);
    const std::size_t len = static_cast<unsigned char>(bytes[8]) | (std::size_t(static_cast<unsigned char>(bytes[9])) << 8);
    REQUIRE(bytes.size() >= 10 + len);
    n.dict = bytes.substr(10, len);
    n.data_offset = 10 + len;
    return n;
}

}  // namespace

TEST_CASE("export-field: writes a .npy v1.0 float32 (N, N, N, 3) array; refuses to overwrite without --force") {
    TempDir dir;
    const Result r = run_ranryu(dir.path(), {"export-field", "--size", "12", "--extent", "0.5", "--octaves", "1:3", "--seed", "9", "--out", "f.npy"});
    INFO(r.describe());
    REQUIRE(r.exit_code == 0);
    const std::string bytes = read_file(dir / "f.npy");
    const Npy n = parse_npy(bytes);
    CHECK(n.major == 1);
    CHECK(n.minor == 0);
    CHECK(n.dict.find("'descr': '<f4'") != std::string::npos);
    CHECK(n.dict.find("'fortran_order': False") != std::string::npos);
    CHECK(n.dict.find("'shape': (12, 12, 12, 3)") != std::string::npos);
    CHECK(n.dict.back() == '\n');
    CHECK(n.data_offset % 64 == 0);
    REQUIRE(bytes.size() == n.data_offset + 12 * 12 * 12 * 3 * sizeof(float));
    double sum2 = 0;
    bool finite = true;
    for (std::size_t i = n.data_offset; i < bytes.size(); i += 4) {
        float v;
        std::memcpy(&v, bytes.data() + i, 4);
        finite = finite && std::isfinite(v);
        sum2 += double(v) * v;
    }
    CHECK(finite);
    CHECK(sum2 > 0.0);
    CHECK(list_dir(dir.path()) == std::vector<std::string>{"f.npy"});   // no temporary left behind

    // Again without --force: refused, the file unchanged.
    const Result again = run_ranryu(dir.path(), {"export-field", "--size", "8", "--out", "f.npy"});
    INFO(again.describe());
    CHECK(again.exit_code == 2);
    REQUIRE(again.err_lines().size() == 1);
    CHECK(again.err_lines()[0].find("--out") != std::string::npos);
    CHECK(read_file(dir / "f.npy") == bytes);

    // With --force: replaced (another size).
    const Result forced = run_ranryu(dir.path(), {"export-field", "--size", "8", "--out", "f.npy", "--force"});
    INFO(forced.describe());
    CHECK(forced.exit_code == 0);
    CHECK(parse_npy(read_file(dir / "f.npy")).dict.find("'shape': (8, 8, 8, 3)") != std::string::npos);
}

TEST_CASE("export-field: bad --size, --octaves, --beta or a missing --out exit 2 naming the option") {
    TempDir dir;
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--size", "7", "--out", "a.npy"}, "--size"},
        {{"--size", "257", "--out", "a.npy"}, "--size"},
        {{"--size", "64x64", "--out", "a.npy"}, "--size"},
        {{"--octaves", "3", "--out", "a.npy"}, "--octaves"},
        {{"--octaves", "4:2", "--out", "a.npy"}, "--octaves"},
        {{"--octaves", "a:b", "--out", "a.npy"}, "--octaves"},
        {{"--beta", "-1", "--out", "a.npy"}, "--beta"},
        {{"--size", "16"}, "--out"},
    };
    for (const auto& [args, option] : cases) {
        std::vector<std::string> argv = {"export-field"};
        argv.insert(argv.end(), args.begin(), args.end());
        const Result r = run_ranryu(dir.path(), argv);
        INFO(option << ": " << r.describe());
        CHECK(r.exit_code == 2);
        REQUIRE(r.err_lines().size() == 1);
        CHECK(r.err_lines()[0].find(option) != std::string::npos);
    }
    CHECK(list_dir(dir.path()).empty());
}
