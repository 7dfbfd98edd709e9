// The one stb_image implementation of the CLI tests.
#include "image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#include <stb_image.h>

namespace ranryu::test {

Image load_png(const std::filesystem::path& path) {
    Image img;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        img.error = "cannot open " + path.string();
        return img;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), signature, 8) != 0) {
        img.error = path.string() + " has no PNG signature";
        return img;
    }
    int w = 0, h = 0, n = 0;
    stbi_uc* px = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &n, 4);
    if (!px) {
        img.error = path.string() + ": " + (stbi_failure_reason() ? stbi_failure_reason() : "cannot decode");
        return img;
    }
    img.width = w;
    img.height = h;
    img.channels = n;
    img.rgba.assign(px, px + std::size_t(w) * std::size_t(h) * 4);
    stbi_image_free(px);
    return img;
}

std::size_t Image::distinct_colours() const {
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i + 3 < rgba.size(); i += 4)
        colours.insert(std::uint32_t(rgba[i]) << 16 | std::uint32_t(rgba[i + 1]) << 8 | std::uint32_t(rgba[i + 2]));
    return colours.size();
}

double Image::luma_stddev() const {
    const std::size_t n = rgba.size() / 4;
    if (n == 0) return 0.0;
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double y = 0.299 * rgba[4 * i] + 0.587 * rgba[4 * i + 1] + 0.114 * rgba[4 * i + 2];
        sum += y;
        sum2 += y * y;
    }
    const double mean = sum / double(n);
    return std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean));
}

}  // namespace ranryu::test
