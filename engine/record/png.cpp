#include "record/png.h"

#include <system_error>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb_image_write.h>

#include "core/error.h"

namespace ranryu::record {

void write_png(const std::filesystem::path& path, int width, int height, const std::uint8_t* rgba) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    if (!stbi_write_png(tmp.c_str(), width, height, 4, rgba, width * 4)) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write " + path.string());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw Error("cannot write " + path.string() + ": " + ec.message());
}

}  // namespace ranryu::record
