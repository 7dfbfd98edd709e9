#pragma once
// Files written whole or not at all: the bytes go to "<path>.tmp", which is renamed over `path`, so
// a reader (or a run interrupted mid-write) never sees half a file. Used by the binary exports
// (surface/ply.h, record/particle_files.h).
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

namespace ranryu {

// Writes the parts one after another. Throws ranryu::Error("<where><reason>") and removes the
// temporary file when it cannot be written or renamed.
void write_whole_file(const std::filesystem::path& path, std::initializer_list<std::string_view> parts,
                      const std::string& where);

}  // namespace ranryu
