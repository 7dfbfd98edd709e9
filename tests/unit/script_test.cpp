// run --script (engine/input/script.h): the line format, and one clear message naming the line for
// every mistake.
#include <catch2/catch.hpp>

#include "core/error.h"
#include "input/commands.h"
#include "input/script.h"

using namespace ranryu;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

TEST_CASE("a run script gives each line's frame and command, comments and blank lines skipped", "[unit][script]") {
    const std::vector<input::Event> e = input::parse_script(
        "# pause, look, go on\n"
        "\n"
        "0 key h\n"
        "3   key space   # trailing comment\n"
        "3 key f12\n"
        "4 drag 12.5 -3\n"
        "4 wheel -2\n"
        "5 panel shading phong\n"
        "5 panel scene falling-block\n"
        "6 panel solver wcsph\n"
        "6 panel pause off\n"
        "7 panel panel on\n"
        "8 panel step\n"
        "9 key 2\n"
        "10 panel quit\n"
        "11 panel viscosity 1e-3\n"
        "11 panel cfl 0.25\n"
        "11 panel turbulence off\n"
        "11 panel amplitude 20\n"
        "12 key t\n",
        "s.txt");
    REQUIRE(e.size() == 18);
    CHECK(e[0].frame == 0);
    CHECK(e[0].line == 3);
    CHECK(e[0].command.kind == input::Kind::toggle_panel);
    CHECK(e[1].frame == 3);
    CHECK(e[1].command.kind == input::Kind::toggle_pause);
    CHECK(e[2].command.kind == input::Kind::screenshot);
    CHECK(e[3].command.kind == input::Kind::drag);
    CHECK(e[3].command.x == 12.5f);
    CHECK(e[3].command.y == -3.0f);
    CHECK(e[4].command.kind == input::Kind::wheel);
    CHECK(e[4].command.x == -2.0f);
    CHECK(e[5].command.kind == input::Kind::shading);
    CHECK(e[5].command.shading == render::Shading::phong);
    CHECK(e[6].command.kind == input::Kind::scene);
    CHECK(scene::bundled().at(std::size_t(e[6].command.index)).name == "falling-block");
    CHECK(e[7].command.kind == input::Kind::solver);
    CHECK(e[7].command.solver == scene::Solver::wcsph);
    CHECK(e[8].command.kind == input::Kind::set_pause);
    CHECK_FALSE(e[8].command.on);
    CHECK(e[9].command.kind == input::Kind::set_panel);
    CHECK(e[9].command.on);
    CHECK(e[10].command.kind == input::Kind::step);
    CHECK(e[11].command.kind == input::Kind::scene);
    CHECK(e[11].command.index == 1);
    CHECK(e[12].command.kind == input::Kind::quit);
    CHECK(e[12].line == 15);
    CHECK(e[13].command.kind == input::Kind::viscosity);
    CHECK(e[13].command.x == 1e-3f);
    CHECK(e[14].command.kind == input::Kind::cfl);
    CHECK(e[14].command.x == 0.25f);
    CHECK(e[15].command.kind == input::Kind::turbulence);
    CHECK_FALSE(e[15].command.on);
    CHECK(e[16].command.kind == input::Kind::amplitude);
    CHECK(e[16].command.x == 20.0f);
    CHECK(e[17].command.kind == input::Kind::toggle_turbulence);
}

TEST_CASE("a bad run script is one InputError naming the script and the line", "[unit][script][bad-input]") {
    struct Case {
        std::string text, says;
    };
    const Case cases[] = {
        {"0 key h\nfive key space\n", "s.txt:2: \"five\": expected a frame number"},
        {"-1 key h\n", "s.txt:1: \"-1\": expected a frame number"},
        {"0\n", "s.txt:1: frame 0 has no event"},
        {"0 key\n", "s.txt:1: expected \"FRAME key NAME\""},
        {"0 key q\n", "s.txt:1: key q: no such key"},
        {"0 press space\n", "s.txt:1: \"press\": no such event"},
        {"0 drag 1\n", "s.txt:1: expected \"FRAME drag DX DY\""},
        {"0 drag 1 x\n", "s.txt:1: drag DY \"x\": expected a number"},
        {"0 wheel inf\n", "s.txt:1: wheel N \"inf\": expected a number"},
        {"0 panel\n", "s.txt:1: panel: name an action"},
        {"0 panel shading toon\n", "s.txt:1: panel shading toon: expected one of"},
        {"0 panel scene nowhere\n", "s.txt:1: panel scene nowhere: no bundled scene of that name"},
        {"0 panel solver sph\n", "s.txt:1: panel solver sph: expected dfsph, wcsph or pbf"},
        {"0 panel pause maybe\n", "s.txt:1: panel pause: expected on or off"},
        {"0 panel step now\n", "s.txt:1: expected \"FRAME panel step\""},
        {"0 panel fly\n", "s.txt:1: panel fly: no such action"},
        {"0 panel cfl 0\n", "s.txt:1: panel cfl 0: expected a Courant number in [0.01, 1]"},
        {"0 panel viscosity -1\n", "s.txt:1: panel viscosity -1: expected m^2/s in [0, 10]"},
        {"0 panel amplitude 0\n", "s.txt:1: panel amplitude 0: expected 1/m in (0, 10000]"},
        {"0 panel amplitude\n", "s.txt:1: expected \"FRAME panel amplitude VALUE\""},
        {"0 panel turbulence\n", "s.txt:1: panel turbulence: expected on or off"},
        {"5 key h\n\n# back in time\n4 key h\n", "s.txt:4: frame 4 comes after frame 5"},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        try {
            input::parse_script(c.text, "s.txt");
            FAIL("accepted");
        } catch (const InputError& e) {
            CHECK_THAT(std::string(e.what()), StartsWith("--script " + c.says));
            CHECK(std::string(e.what()).find('\n') == std::string::npos);
        }
    }
}

TEST_CASE("Replay hands out the events due before a frame, in order", "[unit][script]") {
    input::Replay r(input::parse_script("0 key h\n2 key space\n2 key f12\n5 key escape\n", "s.txt"));
    std::vector<int> lines;
    auto take = [&](std::uint64_t frame) {
        lines.clear();
        for (const input::Event* e; (e = r.next_due(frame)); r.pop()) lines.push_back(e->line);
        return lines;
    };
    CHECK(take(0) == std::vector<int>{1});
    CHECK(take(1).empty());
    CHECK(take(3) == std::vector<int>{2, 3});
    CHECK_FALSE(r.done());
    CHECK(take(5) == std::vector<int>{4});
    CHECK(r.done());
}
