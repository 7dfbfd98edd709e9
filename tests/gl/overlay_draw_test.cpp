// The overlay's draw (render::OverlayDraw, glsl/render/overlay.vert, overlay.frag) against the CPU:
// random axis-aligned quads in two lists, each with a random colour, a 2x2 texture of random texels
// sampled at one texel's centre, a random clip rectangle, and its own index offset within its list and
// (every other quad) a vertex offset, drawn over a cleared target through a display rectangle at a
// random offset with 1 or 2 framebuffer pixels a display pixel (a HiDPI window's), must give every
// pixel the CPU's composite: in draw order, where the pixel's centre lies inside the quad and its
// clip rectangle (both mapped to framebuffer pixels as (p − display_pos)·scale),
//     src = colour · texel,   rgb ← src.rgb · src.a + rgb · (1 − src.a),   a ← src.a + a · (1 − src.a)
// (Dear ImGui's blending), the display's y axis pointing down and the texture's first row at v = 0.
// Tolerance (n + 1)/255 a channel for a pixel under n quads: the clear's conversion to 8 bits and each
// blend's may round the other way on the GPU than on the CPU (1 each), and a difference d in the
// destination carries into the next blend as (1 − a)·d ≤ d, so after n blends |GPU − CPU| ≤ n + 1.
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
    glm::ivec4 rect;   // x0, y0, x1, y1 (framebuffer pixels, top-left origin)
    glm::ivec4 clip;
    std::array<std::uint8_t, 4> colour;
    std::array<std::array<std::uint8_t, 4>, 4> texels;   // the 2x2 texture, rows from the top
    int texel = 0;                                       // the one sampled: row texel / 2, column texel % 2
    int list = 0;
};

// The display the quads are drawn through: framebuffer pixel p is display point p / scale + pos.
struct Display {
    glm::vec2 pos{0.0f};
    float scale = 1.0f;
};

std::uint32_t pack(const std::array<std::uint8_t, 4>& c) {
    return std::uint32_t(c[0]) | std::uint32_t(c[1]) << 8 | std::uint32_t(c[2]) << 16 | std::uint32_t(c[3]) << 24;
}

// The CPU's composite of `quads` in order over `clear` (rows from the top, 8-bit RGBA), and how many
// quads cover each pixel.
struct Composite {
    std::vector<double> rgba;
    std::vector<int> layers;
};
Composite composite(const std::vector<Quad>& quads, const glm::dvec4& clear) {
    Composite out{std::vector<double>(std::size_t(kWidth) * kHeight * 4), std::vector<int>(std::size_t(kWidth) * kHeight, 0)};
    std::vector<double>& img = out.rgba;
    for (std::size_t p = 0; p < img.size(); p += 4)
        for (int c = 0; c < 4; ++c) img[p + std::size_t(c)] = std::round(clear[c] * 255.0);
    // Lists draw in order, and within a list its quads in order.
    for (int list = 0; list < 2; ++list)
        for (const Quad& q : quads) {
            if (q.list != list) continue;
            const int x0 = std::max(q.rect.x, q.clip.x), x1 = std::min(q.rect.z, q.clip.z);
            const int y0 = std::max(q.rect.y, q.clip.y), y1 = std::min(q.rect.w, q.clip.w);
            double src[4];
            const auto& texel = q.texels[std::size_t(q.texel)];
            for (int c = 0; c < 4; ++c) src[c] = (q.colour[std::size_t(c)] / 255.0) * (texel[std::size_t(c)] / 255.0);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const std::size_t pixel = std::size_t(y) * kWidth + std::size_t(x);
                    double* d = &img[pixel * 4];
                    for (int c = 0; c < 3; ++c) d[c] = std::round(255.0 * (src[c] * src[3] + d[c] / 255.0 * (1.0 - src[3])));
                    d[3] = std::round(255.0 * (src[3] + d[3] / 255.0 * (1.0 - src[3])));
                    ++out.layers[pixel];
                }
        }
    return out;
}

// Draws `quads` as two lists, every quad its own command: its six indices at its own index offset in
// its list, and its vertices addressed either through the command's vertex offset (even quads:
// indices 0-3) or by their place in the list (odd quads: no vertex offset).
void draw(render::OverlayDraw& d, const std::vector<Quad>& quads, const std::vector<gl::Texture2D>& textures, const Display& display) {
    std::vector<render::OverlayVertex> vertices[2];
    std::vector<render::OverlayIndex> indices[2];
    std::vector<render::OverlayCommand> commands[2];
    auto to_display = [&](glm::ivec4 r) {
        return glm::vec4(glm::vec2(r.x, r.y) / display.scale + display.pos, glm::vec2(r.z, r.w) / display.scale + display.pos);
    };
    for (std::size_t k = 0; k < quads.size(); ++k) {
        const Quad& q = quads[k];
        auto& v = vertices[q.list];
        auto& i = indices[q.list];
        const auto first = std::uint32_t(v.size()), first_index = std::uint32_t(i.size());
        const std::uint32_t rgba = pack(q.colour);
        const glm::vec4 r = to_display(q.rect);
        const float u = q.texel % 2 ? 0.75f : 0.25f, t = q.texel / 2 ? 0.75f : 0.25f;
        v.push_back({r.x, r.y, u, t, rgba});
        v.push_back({r.z, r.y, u, t, rgba});
        v.push_back({r.z, r.w, u, t, rgba});
        v.push_back({r.x, r.w, u, t, rgba});
        const bool offset = k % 2 == 0;
        const auto base = render::OverlayIndex(offset ? 0 : first);
        for (const int n : {0, 1, 2, 0, 2, 3}) i.push_back(render::OverlayIndex(base + n));
        commands[q.list].push_back({to_display(q.clip), textures[k].id(), first_index, 6, offset ? first : 0u});
    }
    d.begin(vertices[0].size() + vertices[1].size(), indices[0].size() + indices[1].size(), display.pos,
            glm::vec2(kWidth, kHeight) / display.scale, glm::vec2(display.scale));
    for (int l = 0; l < 2; ++l) d.draw_list(vertices[l], indices[l], commands[l]);
    d.end();
}

// The target read back, rows from the top, against the CPU's composite: the channels beyond their
// bound (n + 1 for a pixel under n quads), and the largest difference.
struct Difference {
    std::size_t beyond = 0;
    double largest = 0.0;
};
Difference compare(const gl::RenderTarget& target, const Composite& expected) {
    const std::vector<std::uint8_t> rgba = ranryu::test::read_rgba(target);   // rows from the bottom
    Difference d;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t pixel = std::size_t(y) * kWidth + std::size_t(x);
            for (int c = 0; c < 4; ++c) {
                const double got = rgba[(std::size_t(kHeight - 1 - y) * kWidth + std::size_t(x)) * 4 + std::size_t(c)];
                const double diff = std::abs(got - expected.rgba[pixel * 4 + std::size_t(c)]);
                d.largest = std::max(d.largest, diff);
                if (diff > double(expected.layers[pixel] + 1)) ++d.beyond;
            }
        }
    return d;
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
        for (int c = 0; c < 4; ++c) {
            q.colour[std::size_t(c)] = std::uint8_t(rng.below(256));
            for (auto& t : q.texels) t[std::size_t(c)] = std::uint8_t(rng.below(256));
        }
        q.texel = int(rng.below(4));
        q.list = k < count / 2 ? 0 : 1;
        quads.push_back(q);
    }
    return quads;
}

std::vector<gl::Texture2D> textures_of(const std::vector<Quad>& quads) {
    std::vector<gl::Texture2D> t;
    for (const Quad& q : quads) t.push_back(render::OverlayDraw::texture(q.texels[0].data(), 2, 2));   // the four texels contiguous
    return t;
}

}  // namespace

TEST_CASE("overlay draw: random quads in two lists, with index and vertex offsets, clip rectangles, textures and a display "
          "at an offset and scale 1 or 2, against the CPU's composite within (n + 1)/255 under n quads",
          "[render][overlay]") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    render::OverlayDraw d(FileSource::embedded());
    gl::RenderTarget target(kWidth, kHeight);
    const glm::dvec4 background(0.1, 0.3, 0.8, 1.0);
    for (int round = 0; round < 6; ++round) {   // each region of the ring twice; scale 1, then 2
        const std::vector<Quad> quads = random_quads(rng, 8);
        const std::vector<gl::Texture2D> textures = textures_of(quads);
        // A display origin of whole and half pixels (exact in float), as a window's framebuffer scale
        // makes them: the quads' corners and clips land on framebuffer pixel edges.
        const Display display{glm::vec2(float(rng.below(64)) - 32.0f, float(rng.below(64)) * 0.5f), round < 3 ? 1.0f : 2.0f};
        INFO("display at " << display.pos.x << ", " << display.pos.y << ", scale " << display.scale);
        clear(target, background);
        draw(d, quads, textures, display);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        const Difference d = compare(target, composite(quads, background));
        INFO("frame " << round << ": largest difference " << d.largest << "/255");
        CHECK(d.beyond == 0);
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
        draw(d, quads, textures, Display{});
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return compare(target, composite(quads, background)).beyond;
    };
    CHECK(frame(2) == 0);   // 8 vertices, 12 indices (6 a list): more indices than the room
    CHECK(d.reallocations() == 1);
    const std::size_t vertices = d.vertex_capacity(), indices = d.index_capacity();
    CHECK(vertices >= 8);
    CHECK(indices >= 12);
    CHECK(frame(2) == 0);
    CHECK(frame(1) == 0);
    CHECK(d.reallocations() == 1);
    CHECK(frame(6) == 0);   // 24 vertices: more than any frame before
    CHECK(d.reallocations() == 2);
    CHECK(d.vertex_capacity() >= 24);
    for (int k = 0; k < 4; ++k) CHECK(frame(1 + k) == 0);
    CHECK(d.reallocations() == 2);

    // begin() told of fewer vertices than the lists hold: refused by name, nothing drawn past it.
    const render::OverlayVertex v[4] = {};
    const render::OverlayIndex i[6] = {0, 1, 2, 0, 2, 3};
    d.begin(2, 6, glm::vec2(0.0f), glm::vec2(kWidth, kHeight), glm::vec2(1.0f));
    CHECK_THROWS_WITH(d.draw_list(v, i, {}), Catch::Contains("more than begin() was given"));
    d.end();
    ranryu::test::require_no_gl_errors();
}
