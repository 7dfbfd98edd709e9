#pragma once
// Draws a panel laid out as Dear ImGui lays one out (app/overlay.h) with GL objects made once:
// its program, one vertex array, one vertex and one index buffer. Dear ImGui's own
// OpenGL 3 backend makes a vertex array every frame and a buffer's storage whenever a frame's
// geometry outgrows the last; this one allocates at construction and again only when a frame
// needs more than it ever has (reallocations() counts those), so that a frame's panel costs uploads
// and draws alone.
//
// The buffers hold kRegions regions, written in turn a frame each (a ring): GL orders the uploads
// (glBufferSubData) after the draws queued before them anyway, and the ring spares the driver a wait
// or a copy when the GPU is still drawing from the region a frame before. (Unsynchronised or
// persistent mappings would need a fence a region.) Vertices are Dear ImGui's
// ImDrawVert byte for byte (app/overlay.cpp asserts it): position in display pixels with a top-left
// origin, texture coordinates, RGBA8 colour. Indices are 16-bit (ImDrawIdx); a list longer than
// 65,536 vertices arrives as commands with vertex offsets (ImGuiBackendFlags_RendererHasVtxOffset).
//
// A frame: begin() with its totals and the display, draw_list() for each list, end(). begin() sets
// the viewport to the framebuffer's size, blending (alpha over, the destination's alpha kept as
// Dear ImGui's backends do) and the scissor test; end() turns blending and the scissor off again, the
// state every pass leaves (render/renderer.h). Draws into whatever framebuffer is bound.
#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "shader/program.h"
#include "shader/source.h"

namespace ranryu::render {

struct OverlayVertex {
    float x = 0.0f, y = 0.0f;   // display pixels, top-left origin
    float u = 0.0f, v = 0.0f;
    std::uint32_t rgba = 0;     // R in the lowest byte (Dear ImGui's IM_COL32)
};
static_assert(sizeof(OverlayVertex) == 20);
using OverlayIndex = std::uint16_t;

// One draw of a list: `index_count` indices from `first_index`, each offset by `first_vertex`, within
// the list's own arrays; clipped to `clip` (x0, y0, x1, y1 in display pixels, top-left origin).
struct OverlayCommand {
    glm::vec4 clip{0.0f};
    GLuint texture = 0;
    std::uint32_t first_index = 0, index_count = 0, first_vertex = 0;
};

class OverlayDraw {
public:
    static constexpr std::size_t kRegions = 3;

    // Room for `vertices` and `indices` a frame. Throws ranryu::Error when its shaders fail.
    OverlayDraw(const shader::FileSource& shaders, std::size_t vertices = std::size_t(1) << 15,
                std::size_t indices = std::size_t(1) << 16);

    // An RGBA8 texture of width x height texels from `rgba`, rows from the top (Dear ImGui's font
    // atlas), linearly filtered and clamped, for commands to name. Start-up only.
    static gl::Texture2D texture(const std::uint8_t* rgba, int width, int height);

    // A frame of `vertices` and `indices` in all, over the display rectangle at `display_pos` of
    // `display_size` pixels, `scale` framebuffer pixels a display pixel.
    void begin(std::size_t vertices, std::size_t indices, glm::vec2 display_pos, glm::vec2 display_size, glm::vec2 scale);
    // One list's vertices, indices and commands; together at most the totals given to begin().
    void draw_list(std::span<const OverlayVertex> vertices, std::span<const OverlayIndex> indices,
                   std::span<const OverlayCommand> commands);
    void end();

    std::size_t vertex_capacity() const { return vertex_capacity_; }   // a frame's, in vertices
    std::size_t index_capacity() const { return index_capacity_; }
    std::size_t reallocations() const { return reallocations_; }       // since construction

private:
    void allocate(std::size_t vertices, std::size_t indices);

    shader::Program program_;
    gl::VertexArray vao_;
    gl::Buffer vertices_, indices_;
    std::size_t vertex_capacity_ = 0, index_capacity_ = 0, reallocations_ = 0;
    // The frame under way: its region and how far its lists have filled it.
    std::size_t region_ = kRegions - 1, vertex_fill_ = 0, index_fill_ = 0, frame_vertices_ = 0, frame_indices_ = 0;
    glm::vec2 display_pos_{0.0f}, scale_{1.0f};
    glm::ivec2 framebuffer_{0};
};

}  // namespace ranryu::render
