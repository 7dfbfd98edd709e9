#include <catch2/catch.hpp>

#include "core/error.h"
#include "scene/scene.h"

using ranryu::InputError;
using namespace ranryu::scene;

namespace {
// The message of the InputError that parsing `json` raises ("" if none).
std::string error_of(const std::string& json) {
    try {
        parse(json, "test.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}
const std::string kBlock = R"("particles": {"spacing": 0.1, "blocks": [{"min": [0,0,0], "max": [0.5,0.5,0.5]}]})";
}  // namespace

TEST_CASE("every bundled scene parses and has particles") {
    const auto scenes = bundled();
    REQUIRE(!scenes.empty());
    for (const auto& b : scenes) {
        INFO(b.name);
        const Scene s = load(b.name);
        CHECK(s.particle_count() > 0);
        CHECK(s.initial_positions().size() == s.particle_count());
        CHECK(!s.description.empty());
    }
}

TEST_CASE("lattice blocks place (i + 1/2)·spacing from the block's corner") {
    const Scene s = parse("{" + kBlock + "}", "t");
    REQUIRE(s.particle_count() == 125);
    const auto p = s.initial_positions();
    CHECK(p[0].x == Approx(0.05f));
    CHECK(p[124].z == Approx(0.45f));
}

TEST_CASE("scene errors name the input and the key") {
    CHECK_THAT(error_of("{" + kBlock + ", \"tank\": {\"restitution\": 2}}"),
               Catch::Contains("test.json") && Catch::Contains("tank.restitution") && Catch::Contains("out of range"));
    CHECK_THAT(error_of("{" + kBlock + ", \"colour\": 1}"), Catch::Contains("unknown key \"colour\""));
    CHECK_THAT(error_of("{" + kBlock + ", \"camera\": {\"fov\": 1}}"), Catch::Contains("unknown key \"camera.fov\""));
    CHECK_THAT(error_of("{\"tank\": {"), Catch::Contains("malformed JSON") && Catch::Contains("line 1"));
    CHECK_THAT(error_of("{" + kBlock + ", \"gravity\": [0, 1]}"), Catch::Contains("array of 3 numbers"));
    CHECK_THAT(error_of("{\"particles\": {\"spacing\": 0.1, \"blocks\": [{\"min\": [0,0,0], \"max\": [2,0.5,0.5]}]}}"),
               Catch::Contains("inside the tank"));
    CHECK_THAT(error_of("{}"), Catch::Contains("at least one block"));
    CHECK_THAT(error_of("{" + kBlock + ", \"render\": {\"width\": 10.5}}"), Catch::Contains("render.width"));
    CHECK_THAT(error_of("{" + kBlock + ", \"sph\": {\"neighbour_masks\": 1}}"),
               Catch::Contains("sph.neighbour_masks") && Catch::Contains("true or false"));
    CHECK(!parse("{" + kBlock + ", \"sph\": {\"neighbour_masks\": false}}", "t").sph.neighbour_masks);
}

TEST_CASE("sph.why is a comment on the settings: kept as written, a string, and nothing else changes") {
    const Scene plain = parse("{" + kBlock + ", \"model\": \"sph\"}", "t");
    CHECK(plain.sph.why.empty());
    const Scene s = parse("{" + kBlock + ", \"model\": \"sph\", \"sph\": {\"why\": \"wcsph x2: the cheapest sound setting\"}}", "t");
    CHECK(s.sph.why == "wcsph x2: the cheapest sound setting");
    CHECK(s.sph.solver == plain.sph.solver);
    CHECK(s.sph.cfl == plain.sph.cfl);
    CHECK_THAT(error_of("{" + kBlock + ", \"sph\": {\"why\": 2}}"), Catch::Contains("\"sph.why\" must be a string"));
    for (const BundledScene& b : bundled()) CHECK(b.why == load(b.name).sph.why);
}

TEST_CASE("sph.dfsph_cfl: DFSPH's own Courant number, 0 for sph.cfl, refused between 0 and 0.01") {
    const Scene plain = parse("{" + kBlock + ", \"model\": \"sph\"}", "t");
    CHECK(plain.sph.dfsph_cfl == 0.0f);
    CHECK(plain.sph.courant() == plain.sph.cfl);
    Scene s = parse("{" + kBlock + ", \"model\": \"sph\", \"sph\": {\"dfsph_cfl\": 0.5}}", "t");
    CHECK(s.sph.courant() == 0.5f);
    s.sph.courant() = 0.45f;   // the window's panel writes the one in force
    CHECK(s.sph.dfsph_cfl == 0.45f);
    CHECK(s.sph.cfl == plain.sph.cfl);
    s.sph.solver = Solver::wcsph;
    CHECK(s.sph.courant() == plain.sph.cfl);
    CHECK_THAT(error_of("{" + kBlock + ", \"sph\": {\"dfsph_cfl\": 0.005}}"),
               Catch::Contains("sph.dfsph_cfl") && Catch::Contains("must be 0"));
    CHECK_THAT(error_of("{" + kBlock + ", \"sph\": {\"dfsph_cfl\": 1.5}}"), Catch::Contains("sph.dfsph_cfl") && Catch::Contains("out of range"));
}

TEST_CASE("sph.eliminate_boundary_rows: off by default, the tank at rest sets it, refused without the rows it eliminates") {
    const Scene plain = parse("{" + kBlock + ", \"model\": \"sph\"}", "t");
    CHECK_FALSE(plain.sph.eliminate_boundary_rows);
    CHECK(load("hydrostatic").sph.eliminate_boundary_rows);
    CHECK_FALSE(load("dam-break").sph.eliminate_boundary_rows);
    const Scene s = parse("{" + kBlock + ", \"model\": \"sph\", \"sph\": {\"eliminate_boundary_rows\": true}}", "t");
    CHECK(s.sph.eliminate_boundary_rows);
    CHECK_THAT(error_of("{" + kBlock + ", \"sph\": {\"boundary_rows\": false, \"eliminate_boundary_rows\": true}}"),
               Catch::Contains("sph.eliminate_boundary_rows") && Catch::Contains("needs") && Catch::Contains("sph.boundary_rows"));
}

TEST_CASE("an unknown bundled name lists the bundled scenes") {
    try {
        load("no-such-scene");
        FAIL("no error");
    } catch (const InputError& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains("no-such-scene") && Catch::Contains("falling-block"));
    }
}

TEST_CASE("substeps cover the frame exactly") {
    Scene s = parse("{" + kBlock + ", \"time\": {\"frame_dt\": 0.02, \"substep_dt\": 0.003}}", "t");
    CHECK(s.substeps() == 7);
    s = parse("{" + kBlock + ", \"time\": {\"frame_dt\": 0.02, \"substep_dt\": 0.005}}", "t");
    CHECK(s.substeps() == 4);
}

TEST_CASE("another spacing scales PBF's substeps in inverse proportion, rounding up") {
    // docs/PBF.md "Resolution": the fixed step keeps its Courant number. The dam break's 4 substeps at
    // 12.5 mm become 16 at 3.17 mm and 25 at 2 mm (24 was measured stable on the H100), 2 at 25 mm.
    const Scene s = load("dam-break");
    REQUIRE(s.spacing == Approx(0.0125f));
    REQUIRE(s.sph.pbf.substeps == 4);
    CHECK(with_spacing(s, 0.0125f, "t").sph.pbf.substeps == 4);
    CHECK(with_spacing(s, 0.00317f, "t").sph.pbf.substeps == 16);
    CHECK(with_spacing(s, 0.002f, "t").sph.pbf.substeps == 25);
    CHECK(with_spacing(s, 0.025f, "t").sph.pbf.substeps == 2);
    CHECK(with_spacing(s, 0.1f, "t").sph.pbf.substeps == 1);
    // A whole ratio stays whole through the floats' rounding: the tank at rest's 8 at 12.5 mm are 5 at
    // 20 mm (in doubles 8 · 0.0125f / 0.02f is 5.0000002) and 4 at 25 mm; just past it rounds up.
    const Scene tank = load("hydrostatic");
    REQUIRE(tank.sph.pbf.substeps == 8);
    CHECK(with_spacing(tank, 0.02f, "t").sph.pbf.substeps == 5);
    CHECK(with_spacing(tank, 0.025f, "t").sph.pbf.substeps == 4);
    CHECK(with_spacing(tank, 0.0199f, "t").sph.pbf.substeps == 6);
    // Twice over is the same as once: the substeps follow the spacing, not the path to it (the
    // window's slider moves the spacing many times).
    CHECK(with_spacing(with_spacing(s, 0.005f, "t"), 0.00317f, "t").sph.pbf.substeps == 16);
    CHECK(with_spacing(with_spacing(s, 0.003f, "t"), 0.0125f, "t").sph.pbf.substeps == 4);
    CHECK(with_spacing(with_spacing(with_spacing(s, 0.0047f, "t"), 0.0031f, "t"), 0.0125f, "t").sph.pbf.substeps == 4);
}
