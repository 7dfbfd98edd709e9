#pragma once
// PNG decoding for the end-to-end tests (stb_image; its implementation lives in image.cpp).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ranryu::test {

struct Image {
    int width = 0, height = 0;
    int channels = 0;                 // in the file (3 RGB, 4 RGBA, ...); `rgba` is always 4 per pixel
    std::vector<std::uint8_t> rgba;   // width·height·4, top row first
    std::string error;                // why decoding failed; empty on success

    bool ok() const { return error.empty() && width > 0 && height > 0; }
    std::size_t distinct_colours() const;   // distinct RGB triples
    double luma_stddev() const;             // standard deviation of Rec. 601 luma over all pixels (0..255)
};

// Decodes a PNG file; on failure `error` says why. Checks the PNG signature itself, so a file in
// another format that stb could decode does not pass as a PNG.
Image load_png(const std::filesystem::path& path);

}  // namespace ranryu::test
