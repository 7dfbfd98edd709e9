// The window's keys (engine/input/commands.h): each one has a command, and the help lists them all.
#include <catch2/catch.hpp>

#include "input/commands.h"

using namespace ranryu;
using Catch::Matchers::Contains;

TEST_CASE("every key in the help has a command, and the keys' help lists them all", "[unit][keys]") {
    const std::string help = input::keys_help();
    for (const input::Key& k : input::keys()) {
        INFO(k.name);
        if (k.name == "1-9") CHECK(input::key_command("1"));
        else CHECK(input::key_command(k.name));
        CHECK_THAT(help, Contains(std::string(k.help)));
    }
    CHECK_FALSE(input::key_command("q"));
    CHECK_FALSE(input::key_command(std::to_string(scene::bundled().size() + 1)));   // past the bundled scenes
}
