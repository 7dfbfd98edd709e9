#include "render/overlay_draw.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "core/error.h"
#include "render/overlay.h"

namespace ranryu::render {

OverlayDraw::OverlayDraw(const shader::FileSource& shaders, std::size_t vertices, std::size_t indices)
    : program_(shader::Program::graphics(shaders, "render/overlay.vert", "render/overlay.frag")) {
    // OverlayVertex: position at byte 0, uv at 8, colour at 16, stride 20; the buffers are attached
    // here, once (the vertex binding point's buffer and the element buffer are the array's state).
    glBindVertexArray(vao_.id());
    glEnableVertexAttribArray(RANRYU_ATTR_OVERLAY_POSITION);
    glEnableVertexAttribArray(RANRYU_ATTR_OVERLAY_UV);
    glEnableVertexAttribArray(RANRYU_ATTR_OVERLAY_COLOR);
    glVertexAttribFormat(RANRYU_ATTR_OVERLAY_POSITION, 2, GL_FLOAT, GL_FALSE, offsetof(OverlayVertex, x));
    glVertexAttribFormat(RANRYU_ATTR_OVERLAY_UV, 2, GL_FLOAT, GL_FALSE, offsetof(OverlayVertex, u));
    glVertexAttribFormat(RANRYU_ATTR_OVERLAY_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(OverlayVertex, rgba));
    for (GLuint a : {GLuint(RANRYU_ATTR_OVERLAY_POSITION), GLuint(RANRYU_ATTR_OVERLAY_UV), GLuint(RANRYU_ATTR_OVERLAY_COLOR)})
        glVertexAttribBinding(a, 0);
    glBindVertexArray(0);
    gl::label(GL_VERTEX_ARRAY, vao_.id(), "overlay.vao");
    allocate(std::max<std::size_t>(vertices, 1), std::max<std::size_t>(indices, 1));
    reallocations_ = 0;
}

void OverlayDraw::allocate(std::size_t vertices, std::size_t indices) {
    vertices_ = gl::Buffer(kRegions * vertices * sizeof(OverlayVertex), GL_STREAM_DRAW, nullptr, "overlay.vertices");
    indices_ = gl::Buffer(kRegions * indices * sizeof(OverlayIndex), GL_STREAM_DRAW, nullptr, "overlay.indices");
    vertex_capacity_ = vertices, index_capacity_ = indices;
    glBindVertexArray(vao_.id());
    glBindVertexBuffer(0, vertices_.id(), 0, sizeof(OverlayVertex));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.id());
    glBindVertexArray(0);
    ++reallocations_;
}

gl::Texture2D OverlayDraw::texture(const std::uint8_t* rgba, int width, int height) {
    gl::Texture2D t(GL_RGBA8, width, height, "overlay.texture");
    glBindTexture(GL_TEXTURE_2D, t.id());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    // Rows from the top as given: texture coordinate v = 0 is the first row, as Dear ImGui's are.
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

void OverlayDraw::begin(std::size_t vertices, std::size_t indices, glm::vec2 display_pos, glm::vec2 display_size, glm::vec2 scale) {
    if (vertices > vertex_capacity_ || indices > index_capacity_) {
        // A panel larger than any before: room for twice what it needs, so that one that keeps
        // growing reallocates a few times, not every frame.
        allocate(std::max(vertex_capacity_, 2 * vertices), std::max(index_capacity_, 2 * indices));
    }
    region_ = (region_ + 1) % kRegions;
    vertex_fill_ = index_fill_ = 0;
    frame_vertices_ = vertices, frame_indices_ = indices;
    display_pos_ = display_pos, scale_ = scale;
    framebuffer_ = glm::ivec2(std::lround(display_size.x * scale.x), std::lround(display_size.y * scale.y));

    glViewport(0, 0, framebuffer_.x, framebuffer_.y);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_SCISSOR_TEST);
    program_.use();
    glUniform4f(RANRYU_LOC_OVERLAY_DISPLAY, display_pos.x, display_pos.y, display_size.x, display_size.y);
    glActiveTexture(GL_TEXTURE0 + RANRYU_OVERLAY_TEXTURE_UNIT);
    glBindVertexArray(vao_.id());
}

void OverlayDraw::draw_list(std::span<const OverlayVertex> vertices, std::span<const OverlayIndex> indices,
                            std::span<const OverlayCommand> commands) {
    if (vertex_fill_ + vertices.size() > frame_vertices_ || index_fill_ + indices.size() > frame_indices_)
        throw Error("OverlayDraw: the frame's lists hold more than begin() was given (" + std::to_string(frame_vertices_) +
                    " vertices, " + std::to_string(frame_indices_) + " indices)");
    const std::size_t first_vertex = region_ * vertex_capacity_ + vertex_fill_;
    const std::size_t first_index = region_ * index_capacity_ + index_fill_;
    vertices_.upload(vertices.data(), vertices.size_bytes(), first_vertex * sizeof(OverlayVertex));
    indices_.upload(indices.data(), indices.size_bytes(), first_index * sizeof(OverlayIndex));
    vertex_fill_ += vertices.size(), index_fill_ += indices.size();

    GLuint bound = ~0u;   // none yet: a command's texture 0 is bound too
    for (const OverlayCommand& c : commands) {
        if (c.index_count == 0 || std::size_t(c.first_index) + c.index_count > indices.size()) continue;
        // The clip rectangle in framebuffer pixels, truncated as Dear ImGui's own backends do; GL's
        // scissor counts rows from the bottom.
        const glm::vec2 lo = (glm::vec2(c.clip.x, c.clip.y) - display_pos_) * scale_;
        const glm::vec2 hi = (glm::vec2(c.clip.z, c.clip.w) - display_pos_) * scale_;
        const int x0 = std::max(0, int(lo.x)), y0 = std::max(0, int(lo.y));
        const int x1 = std::min(framebuffer_.x, int(hi.x)), y1 = std::min(framebuffer_.y, int(hi.y));
        if (x1 <= x0 || y1 <= y0) continue;
        glScissor(x0, framebuffer_.y - y1, x1 - x0, y1 - y0);
        if (c.texture != bound) glBindTexture(GL_TEXTURE_2D, bound = c.texture);
        glDrawElementsBaseVertex(GL_TRIANGLES, GLsizei(c.index_count), GL_UNSIGNED_SHORT,
                                 reinterpret_cast<const void*>((first_index + c.first_index) * sizeof(OverlayIndex)),
                                 GLint(first_vertex + c.first_vertex));
    }
}

void OverlayDraw::end() {
    glBindVertexArray(0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
}

}  // namespace ranryu::render
