#pragma once
// Files written whole or not at all: the bytes go to "<path>.tmp", which is renamed over `path`, so
// a reader (or a run interrupted mid-write) never sees half a file. Used by the binary exports
// (surface/ply.h, record/particle_files.h) and the checkpoints (frame/checkpoint.h).
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

namespace ranryu {

// Writes the parts one after another. Throws ranryu::Error("<where><reason>") and removes the
// temporary file when it cannot be written or renamed. `sync`: the file is flushed to disk (fsync)
// before the rename, and its folder after, so a machine that goes down just then keeps the old file
// or the new one, never an empty one (the checkpoints; the per-frame exports do without).
void write_whole_file(const std::filesystem::path& path, std::span<const std::string_view> parts, const std::string& where,
                      bool sync = false);
inline void write_whole_file(const std::filesystem::path& path, std::initializer_list<std::string_view> parts,
                             const std::string& where) {
    write_whole_file(path, std::span<const std::string_view>(parts.begin(), parts.size()), where);
}

}  // namespace ranryu
