#include "support/gl_fixture.h"
#include "support/sph_rig.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace {
using ranryu::scene::Obstacle;

// Signed distance to the obstacle's surface, negative inside.
float sdf(const Obstacle& o, glm::vec3 p) {
    if (o.kind == Obstacle::Kind::sphere) return glm::length(p - o.center) - o.radius;
    const glm::vec3 c = 0.5f * (o.min + o.max), e = 0.5f * (o.max - o.min);
    const glm::vec3 q = glm::abs(p - c) - e;
    return glm::length(glm::max(q, 0.0f)) + std::min(std::max({q.x, q.y, q.z}), 0.0f);
}
}  // namespace

TEST_CASE("obstacle: explore", "[.explore]") {
    const char* path = std::getenv("SCENE");
    REQUIRE(path);
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    ranryu::test::SphRig rig(ss.str(), path);
    const int frames = std::getenv("FRAMES") ? std::atoi(std::getenv("FRAMES")) : 40;
    const auto& s = rig.scene;
    std::printf("particles %zu boundary %zu c %g\n", rig.sph.count(), rig.sph.boundary_count(), rig.sph.params().sound_speed);
    {
        auto x0 = s.initial_positions();
        auto v0 = s.initial_velocities();
        for (std::size_t i = 0; i < x0.size(); ++i) x0[i].w = float(i);
        rig.sph.upload_state(x0, v0);
    }
    std::vector<std::vector<glm::vec4>> hist;
    for (int f = 0; f < frames; ++f) {
        rig.frame(std::uint64_t(f));
        const auto x = rig.read(rig.sph.positions());
        const auto v = rig.read(rig.sph.velocities());
        int inside = 0, out = 0;
        float deepest = 0.0f;
        std::size_t worst = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const glm::vec3 p(x[i]);
            for (const Obstacle& o : s.obstacles) {
                const float d = sdf(o, p);
                if (d < 0.0f) {
                    ++inside;
                    if (d < deepest) deepest = d, worst = i;
                }
            }
            if (glm::any(glm::lessThan(p, s.tank_min)) || p.x > s.tank_max.x || p.z > s.tank_max.z) ++out;
        }
        {
            std::vector<glm::vec4> byid(x.size());
            for (std::size_t i = 0; i < x.size(); ++i) byid[std::size_t(x[i].w)] = glm::vec4(glm::vec3(x[i]), 0.0f);
            hist.push_back(byid);
        }
        const auto st = rig.step();
        float vmax = 0;
        for (auto& u : v) vmax = std::max(vmax, glm::length(glm::vec3(u)));
        std::printf("frame %d t %.4f substeps %d inside %d (deepest %.4f at %zu: %.4f %.4f %.4f v %.3f %.3f %.3f) outside-tank %d vmax %.3f\n", f,
                    st.time, rig.sph.substeps_this_frame(), inside, deepest, worst, x[worst].x, x[worst].y, x[worst].z,
                    v[worst].x, v[worst].y, v[worst].z, out, vmax);
        if (std::getenv("DUMP") && inside > 0) {
            for (std::size_t i = 0; i < x.size(); ++i)
                for (const Obstacle& o : s.obstacles)
                    if (sdf(o, glm::vec3(x[i])) < 0.0f)
                        std::printf("   in %zu x %.4f %.4f %.4f d %.4f v %.3f %.3f %.3f\n", i, x[i].x, x[i].y, x[i].z,
                                    sdf(o, glm::vec3(x[i])), v[i].x, v[i].y, v[i].z);
        }
        if (std::getenv("DUMP"))
            for (std::size_t i = 0; i < x.size(); ++i) {
                const glm::vec3 p(x[i]);
                if (glm::any(glm::lessThan(p, s.tank_min)) || p.x > s.tank_max.x || p.z > s.tank_max.z)
                    std::printf("   out %zu x %.4f %.4f %.4f v %.3f %.3f %.3f\n", i, p.x, p.y, p.z, v[i].x, v[i].y, v[i].z);
            }
        if (rig.sph.instability()) {
            std::printf("instability: %s\n", rig.sph.instability()->message().c_str());
            break;
        }
    }
    rig.finish();
    // Trajectories of particles that were ever beyond a side wall by more than dx/2.
    const std::size_t n = hist.back().size();
    int shown = 0;
    for (std::size_t id = 0; id < n && shown < 12; ++id) {
        bool bad = false;
        for (auto& h : hist) {
            const glm::vec3 p(h[id]);
            bad |= p.x < s.tank_min.x - 0.5f * s.spacing || p.z < s.tank_min.z - 0.5f * s.spacing ||
                   p.x > s.tank_max.x + 0.5f * s.spacing || p.z > s.tank_max.z + 0.5f * s.spacing || p.y < s.tank_min.y - 0.5f * s.spacing;
        }
        if (!bad) continue;
        ++shown;
        std::printf("id %zu:", id);
        for (std::size_t f = 0; f < hist.size(); ++f)
            std::printf(" [%zu] %.3f %.3f %.3f", f, hist[f][id].x, hist[f][id].y, hist[f][id].z);
        std::printf("\n");
    }
}
