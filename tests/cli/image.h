#pragma once
// PNG decoding for the end-to-end tests (stb_image; its implementation lives in image.cpp).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

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

// Checks that a PNG is whole: it ends with its IEND chunk (length 0, "IEND", its CRC) and decodes at
// the size asked (a file cut short by a stopped run fails here).
inline void check_whole_png(const std::filesystem::path& file, int width, int height) {
    INFO(file.string());
    std::FILE* f = std::fopen(file.c_str(), "rb");
    REQUIRE(f);
    std::string bytes;
    char buf[65536];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) bytes.append(buf, n);
    std::fclose(f);
    static const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    REQUIRE(bytes.size() > iend.size());
    CHECK(bytes.compare(bytes.size() - iend.size(), iend.size(), iend) == 0);
    const Image img = load_png(file);
    INFO(img.error);
    REQUIRE(img.ok());
    CHECK(img.width == width);
    CHECK(img.height == height);
}

}  // namespace ranryu::test
