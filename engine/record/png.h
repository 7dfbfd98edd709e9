#pragma once
// PNG files written whole or not at all: the image goes to "<path>.tmp" and is renamed into place,
// so an interrupted run never leaves a truncated frame.
#include <cstdint>
#include <filesystem>

namespace ranryu::record {

// `rgba`: width·height RGBA8 pixels, top row first. Throws ranryu::Error naming the file on failure.
void write_png(const std::filesystem::path& path, int width, int height, const std::uint8_t* rgba);

}  // namespace ranryu::record
