#pragma once
// Files embedded in the binary at build time (cmake/Embed.cmake): shaders and bundled scenes.
#include <string_view>

namespace ranryu {
struct EmbeddedFile {
    std::string_view path;   // relative to its root (glsl/ or media/)
    std::string_view text;
};
}  // namespace ranryu
