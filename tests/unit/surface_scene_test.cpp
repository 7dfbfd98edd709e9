// The scene's optional "surface" object: defaults, values, and errors that name the key.
#include <catch2/catch.hpp>

#include "core/error.h"
#include "scene/scene.h"

using ranryu::scene::parse;
using Catch::Matchers::Contains;

namespace {
const std::string kBlock = R"("particles": {"spacing": 0.1, "blocks": [{"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]}]})";
}

TEST_CASE("scene surface settings: defaults and values") {
    auto s = parse("{" + kBlock + "}", "t");
    CHECK(s.surface.node_spacing == 0.5f);
    CHECK(s.surface.max_dims == 512);
    CHECK(s.surface.max_nodes == (1 << 23));
    CHECK(s.surface.anisotropic);
    CHECK(s.surface.max_vertices == (1 << 22));
    s = parse("{" + kBlock + R"(, "surface": {"node_spacing": 1, "max_dims": 64, "max_nodes": 5000, "anisotropic": false,
               "max_vertices": 3000, "absorption": [1, 2, 3]}})", "t");
    CHECK(s.surface.max_nodes == 5000);
    CHECK(!s.surface.anisotropic);
    CHECK(s.surface.node_spacing == 1.0f);
    CHECK(s.surface.max_dims == 64);
    CHECK(s.surface.max_vertices == 3000);
    CHECK(s.surface.absorption == glm::vec3(1.0f, 2.0f, 3.0f));
}

TEST_CASE("scene surface settings: unknown keys and out-of-range values name the key") {
    const auto error = [](const std::string& surface) {
        try {
            parse("{" + kBlock + ", \"surface\": " + surface + "}", "t.json");
        } catch (const ranryu::InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(error(R"({"node_spacin": 1})"), Contains("unknown key \"surface.node_spacin\""));
    CHECK_THAT(error(R"({"node_spacing": 0})"), Contains("\"surface.node_spacing\" = 0 is out of range"));
    CHECK_THAT(error(R"({"max_dims": 2})"), Contains("\"surface.max_dims\" = 2 is out of range"));
    CHECK_THAT(error(R"({"max_dims": 600})"), Contains("\"surface.max_dims\""));
    CHECK_THAT(error(R"({"max_dims": 10.5})"), Contains("must be a whole number"));
    CHECK_THAT(error(R"({"max_nodes": 63})"), Contains("\"surface.max_nodes\" = 63 is out of range"));
    CHECK_THAT(error(R"({"anisotropic": 1})"), Contains("\"surface.anisotropic\" must be true or false"));
    CHECK_THAT(error(R"({"max_vertices": 1})"), Contains("\"surface.max_vertices\" = 1 is out of range"));
    CHECK_THAT(error(R"({"absorption": [1, -1, 0]})"), Contains("\"surface.absorption[1]\""));
    CHECK_THAT(error(R"(3)"), Contains("\"surface\" must be an object"));
    CHECK_THAT(error(R"({"node_spacing": 1})"), Contains("no error"));
}
