#pragma once
// The colour of a render target read back as 8-bit RGBA, rows from the bottom (tests only: a
// synchronous glReadPixels, never in the frame path).
#include <cstdint>
#include <vector>

#include "gl/gl.h"
#include "gl/objects.h"

namespace ranryu::test {

inline std::vector<std::uint8_t> read_rgba(const gl::RenderTarget& target) {
    std::vector<std::uint8_t> rgba(std::size_t(target.width()) * std::size_t(target.height()) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, target.width(), target.height(), GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return rgba;
}

// A texture's level 0 read back as floats, `channels` a texel of `format` (GL_RED, GL_RGBA,
// GL_DEPTH_COMPONENT), rows from the bottom (tests only).
inline void read_texture(const gl::Texture2D& t, GLenum format, std::vector<float>& out, int channels) {
    out.resize(std::size_t(t.width()) * std::size_t(t.height()) * std::size_t(channels));
    glBindTexture(GL_TEXTURE_2D, t.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, format, GL_FLOAT, out.data());
    glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace ranryu::test
