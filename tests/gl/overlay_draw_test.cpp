// The overlay's draw (render::OverlayDraw, glsl/render/overlay.vert, overlay.frag) against the CPU:
// random axis-aligned quads in two lists, each with a random colour, a 1x1 texture of a random colour,
// a random clip rectangle and (within its list) a vertex offset, drawn over a cleared target, must give
// every pixel the CPU's composite: in draw order, where the pixel's centre lies inside the quad and
// its clip rectangle,
//     src = colour · texel,   rgb ← src.rgb · src.a + rgb · (1 − src.a),   a ← src.a + a · (1 − src.a)
// (Dear ImGui's blending), the display's y axis pointing down. Tolerance 2/255 a channel: each blend
// is done in float and stored in 8 bits (0.5 of rounding), the CPU rounds alike, and a pixel under
// several quads carries a rounding difference of one into the next blend.
// Then the buffers' contract: frames that fit reallocate nothing; a frame larger than any before
// reallocates once and draws the same; lists holding more than begin() was given are refused.
#include "support/gl_fixture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/error.h"
#include "gl/objects.h"
#include "render/overlay_draw.h"
#include "shader/source.h"
#include "support/read_pixels.h"

namespace {

namespace render = ranryu::render;
namespace gl = ranryu::gl;
using ranryu::shader::FileSource;
constexpr int kWidth = 96, kHeight = 64;

struct Quad {
    glm::ivec4 rect;   // x0, y0, x1, y1 (display pixels, top-left origin)
    glm::ivec4 clip;
    std::array<std::uint8_t, 4> colour, texel;
    int list = 0;
};

std::uint32_t pack(const std::array<std::uint8_t, 4>& c) {
    return std::uint32_t(c[0]) | std::uint32_t(c[1]) << 8 | std::uint32_t(c[2]) << 16 | std::uint32_t(c[3]) << 24;
}

// The CPU's composite of `quads` in order over `clear` (rows from the top, 8-bit RGBA).
std::vector<double> composite(const std::vector<Quad>& quads, const glm::dvec4& clear) {
    std::vector<double> img(std::size_t(kWidth) * kHeight * 4);
    for (std::size_t p = 0; p < img.size(); p += 4)
        for (int c = 0; c < 4; ++c) img[p + std::size_t(c)] = std::round(clear[c] * 255.0);
    // Lists draw in order, and within a list its quads in order.
    for (int list = 0; list < 2; ++list)
        for (const Quad& q : quads) {
            if (q.list != list) continue;
            const int x0 = std::max(q.rect.x, q.clip.x), x1 = std::min(q.rect.z, q.clip.z);
            const int y0 = std::max(q.rect.y, q.clip.y), y1 = std::min(q.rect.w, q.clip.w);
            double src[4];
            for (int c = 0; c < 4; ++c) src[c] = (q.colour[c] / 255.0) * (q.texel[c] / 255.0);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    double* d = &img[(std::size_t(y) * kWidth + std::size_t(x)) * 4];
                    for (int c = 0; c < 3; ++c) d[c] = std::round(255.0 * (src[c] * src[3] + d[c] / 255.0 * (1.0 - src[3])));
                    d[3] = std::round(255.0 * (src[3] + d[3] / 255.0 * (1.0 - src[3])));
                }
        }
    return img;
}

// Draws `quads` as two lists, every quad its own command with its own vertex offset (the quads'
// vertices one after another in their list, the indices 0-5 of one quad shared by all).
void draw(render::OverlayDraw& d, const std::vector<Quad>& quads, const std::vector<gl::Texture2D>& textures) {
    std::vector<render::OverlayVertex> vertices[2];
    std::vector<render::OverlayIndex> indices[2];
    std::vector<render::OverlayCommand> commands[2];
    for (std::size_t k = 0; k < quads.size(); ++k) {
        const Quad& q = quads[k];
        auto& v = vertices[q.list];
        const auto first = std::uint32_t(v.size());
        const std::uint32_t rgba = pack(q.colour);
        const float x0 = float(q.rect.x), y0 = float(q.rect.y), x1 = float(q.rect.z), y1 = float(q.rect.w);
        v.push_back({x0, y0, 0.5f, 0.5f, rgba});
        v.push_back({x1, y0, 0.5f, 0.5f, rgba});
        v.push_back({x1, y1, 0.5f, 0.5f, rgba});
        v.push_back({x0, y1, 0.5f, 0.5f, rgba});
        if (indices[q.list].empty()) indices[q.list] = {0, 1, 2, 0, 2, 3};
        commands[q.list].push_back({glm::vec4(q.clip), textures[k].id(), 0, 6, first});
    }
    d.begin(vertices[0].size() + vertices[1].size(), indices[0].size() + indices[1].size(), glm::vec2(0.0f),
            glm::vec2(kWidth, kHeight), glm::vec2(1.0f));
    for (int l = 0; l < 2; ++l) d.draw_list(vertices[l], indices[l], commands[l]);
    d.end();
}

// The target read back, rows from the top, against the CPU's composite: the largest difference.
double largest_difference(const gl::RenderTarget& target, const std::vector<double>& expected) {
    const std::vector<std::uint8_t> rgba = ranryu::test::read_rgba(target);   // rows from the bottom
    double most = 0.0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            for (int c = 0; c < 4; ++c) {
                const double got = rgba[(std::size_t(kHeight - 1 - y) * kWidth + std::size_t(x)) * 4 + std::size_t(c)];
                most = std::max(most, std::abs(got - expected[(std::size_t(y) * kWidth + std::size_t(x)) * 4 + std::size_t(c)]));
            }
    return most;
}

void clear(const gl::RenderTarget& target, const glm::dvec4& c) {
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glViewport(0, 0, kWidth, kHeight);
    glClearColor(float(c.r), float(c.g), float(c.b), float(c.a));
    glClear(GL_COLOR_BUFFER_BIT);
}

std::vector<Quad> random_quads(ranryu::test::Random& rng, int count) {
    std::vector<Quad> quads;
    auto span = [&](int extent) {
        int a = int(rng.below(unsigned(extent))), b = int(rng.below(unsigned(extent)));
        if (a > b) std::swap(a, b);
        return glm::ivec2(a, b + 1);
    };
    for (int k = 0; k < count; ++k) {
        Quad q;
        const glm::ivec2 x = span(kWidth), y = span(kHeight), cx = span(kWidth), cy = span(kHeight);
        q.rect = {x.x, y.x, x.y, y.y};
        q.clip = k % 3 == 0 ? glm::ivec4(0, 0, kWidth, kHeight) : glm::ivec4(cx.x, cy.x, cx.y, cy.y);
        for (int c = 0; c < 4; ++c) q.colour[std::size_t(c)] = std::uint8_t(rng.below(256)), q.texel[std::size_t(c)] = std::uint8_t(rng.below(256));
        q.list = k < count / 2 ? 0 : 1;
        quads.push_back(q);
    }
    return quads;
}

std::vector<gl::Texture2D> textures_of(const std::vector<Quad>& quads) {
    std::vector<gl::Texture2D> t;
    for (const Quad& q : quads) t.push_back(render::OverlayDraw::texture(q.texel.data(), 1, 1));
    return t;
}

}  // namespace

TEST_CASE("overlay draw: random quads in two lists, with vertex offsets, clip rectangles and textures, against the CPU's "
          "composite within 2/255",
          "[render][overlay]") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    render::OverlayDraw d(FileSource::embedded());
    gl::RenderTarget target(kWidth, kHeight);
    const glm::dvec4 background(0.1, 0.3, 0.8, 1.0);
    for (int round = 0; round < 3; ++round) {   // three frames: each region of the ring once
        const std::vector<Quad> quads = random_quads(rng, 8);
        const std::vector<gl::Texture2D> textures = textures_of(quads);
        clear(target, background);
        draw(d, quads, textures);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        INFO("frame " << round);
        CHECK(largest_difference(target, composite(quads, background)) <= 2.0);
    }
    CHECK(d.reallocations() == 0);
    // The draw leaves blending and the scissor test off, as every pass does.
    CHECK_FALSE(glIsEnabled(GL_BLEND));
    CHECK_FALSE(glIsEnabled(GL_SCISSOR_TEST));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("overlay draw: frames that fit reallocate nothing, one larger than any before reallocates once and draws the same, "
          "lists beyond begin()'s totals are refused",
          "[render][overlay]") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    render::OverlayDraw d(FileSource::embedded(), 8, 6);   // room for two quads' vertices, one quad's indices a list
    gl::RenderTarget target(kWidth, kHeight);
    const glm::dvec4 background(0.0, 0.0, 0.0, 1.0);
    auto frame = [&](int count) {
        const std::vector<Quad> quads = random_quads(rng, count);
        const std::vector<gl::Texture2D> textures = textures_of(quads);
        clear(target, background);
        draw(d, quads, textures);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return largest_difference(target, composite(quads, background));
    };
    CHECK(frame(2) <= 2.0);   // 8 vertices, 12 indices (6 a list): more indices than the room
    CHECK(d.reallocations() == 1);
    const std::size_t vertices = d.vertex_capacity(), indices = d.index_capacity();
    CHECK(vertices >= 8);
    CHECK(indices >= 12);
    CHECK(frame(2) <= 2.0);
    CHECK(frame(1) <= 2.0);
    CHECK(d.reallocations() == 1);
    CHECK(frame(6) <= 2.0);   // 24 vertices: more than any frame before
    CHECK(d.reallocations() == 2);
    CHECK(d.vertex_capacity() >= 24);
    for (int k = 0; k < 4; ++k) CHECK(frame(1 + k) <= 2.0);
    CHECK(d.reallocations() == 2);

    // begin() told of fewer vertices than the lists hold: refused by name, nothing drawn past it.
    const render::OverlayVertex v[4] = {};
    const render::OverlayIndex i[6] = {0, 1, 2, 0, 2, 3};
    d.begin(2, 6, glm::vec2(0.0f), glm::vec2(kWidth, kHeight), glm::vec2(1.0f));
    CHECK_THROWS_WITH(d.draw_list(v, i, {}), Catch::Contains("more than begin() was given"));
    d.end();
    ranryu::test::require_no_gl_errors();
}
