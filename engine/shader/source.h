#pragma once
// Where shader text comes from, and the include step that GL 4.3 core lacks.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ranryu::shader {

// A read-only tree of shader files addressed by paths relative to glsl/ ("sim/integrate.comp").
class FileSource {
public:
    // The files embedded at build time (cmake/Embed.cmake).
    static FileSource embedded();
    // The files under `root`, read when asked (for editing shaders without rebuilding).
    static FileSource directory(std::filesystem::path root);
    // In-memory files, for tests of the include step.
    static FileSource memory(std::vector<std::pair<std::string, std::string>> files);

    std::optional<std::string> read(const std::string& path) const;
    std::string describe() const;   // "embedded shaders" or the folder

private:
    enum class Kind { embedded, directory, memory } kind_ = Kind::embedded;
    std::filesystem::path root_;
    std::vector<std::pair<std::string, std::string>> files_;
};

// The source string given to glShaderSource and the files it was made from. `files[k]` is the file
// that GLSL source-string number k refers to in `#line` directives and the driver's log.
struct Preprocessed {
    std::string text;
    std::vector<std::string> files;
};

// Resolves `#include "path"` (relative to the including file, then to the root), once per file
// (like #pragma once), and inserts `defines` (lines of "#define ...") right after `#version`.
// `#include <...>` lines are C++'s (in headers shared with C++) and become blank lines.
// `#line` directives keep every line's file and number right. Throws ranryu::Error naming the
// including file and line when an include is missing, and the file when `path` itself is missing
// or has no #version line.
Preprocessed preprocess(const FileSource& source, const std::string& path, std::string_view defines = {});

// Rewrites a driver's compile log so that locations read "file:line": Mesa's "0:12(5):" and
// NVIDIA's "0(12) :" forms, where 0 is the source-string number.
std::string annotate_log(std::string_view log, const std::vector<std::string>& files);

}  // namespace ranryu::shader
