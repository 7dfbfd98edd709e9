#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

TEST_CASE("ranryu --version exits 0") {
    const std::string cmd = std::string(RANRYU_BIN) + " --version > /dev/null";
    CHECK(std::system(cmd.c_str()) == 0);
}
