#include "shader/source.h"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "core/embedded.h"
#include "core/error.h"

namespace ranryu::shader {

extern const EmbeddedFile kEmbeddedFiles[];
extern const unsigned kEmbeddedFileCount;

FileSource FileSource::embedded() { return FileSource{}; }

FileSource FileSource::directory(std::filesystem::path root) {
    FileSource s;
    s.kind_ = Kind::directory;
    s.root_ = std::move(root);
    return s;
}

FileSource FileSource::memory(std::vector<std::pair<std::string, std::string>> files) {
    FileSource s;
    s.kind_ = Kind::memory;
    s.files_ = std::move(files);
    return s;
}

std::optional<std::string> FileSource::read(const std::string& path) const {
    switch (kind_) {
        case Kind::embedded:
            for (unsigned i = 0; i < kEmbeddedFileCount; ++i)
                if (kEmbeddedFiles[i].path == path) return std::string(kEmbeddedFiles[i].text);
            return std::nullopt;
        case Kind::directory: {
            std::ifstream in(root_ / path, std::ios::binary);
            if (!in) return std::nullopt;
            std::ostringstream ss;
            ss << in.rdbuf();
            return ss.str();
        }
        case Kind::memory:
            for (const auto& [p, text] : files_)
                if (p == path) return text;
            return std::nullopt;
    }
    return std::nullopt;
}

std::string FileSource::describe() const {
    switch (kind_) {
        case Kind::embedded: return "embedded shaders";
        case Kind::directory: return root_.string();
        case Kind::memory: return "in-memory shaders";
    }
    return {};
}

namespace {

// Source string k's line L is emitted as line k·kLineStride + L, so the file is known from the
// line number alone: Mesa reports many errors in source string 0 whatever #line said.
constexpr long kLineStride = 1000000;
std::string line_directive(int line, int id) {
    return "#line " + std::to_string(long(id) * kLineStride + line) + " " + std::to_string(id) + "\n";
}

std::string normalise(const std::filesystem::path& p) { return p.lexically_normal().generic_string(); }

std::vector<std::string_view> split_lines(std::string_view text) {
    std::vector<std::string_view> lines;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) {
            if (start < text.size()) lines.push_back(text.substr(start));
            break;
        }
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

// If `line` is an #include directive, returns its target and whether it was in quotes.
std::optional<std::pair<std::string, bool>> include_target(std::string_view line) {
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos || line[i] != '#') return std::nullopt;
    i = line.find_first_not_of(" \t", i + 1);
    if (i == std::string_view::npos || line.substr(i, 7) != "include") return std::nullopt;
    i = line.find_first_not_of(" \t", i + 7);
    if (i == std::string_view::npos) return std::nullopt;
    const char open = line[i];
    const char close = open == '"' ? '"' : open == '<' ? '>' : '\0';
    if (!close) return std::nullopt;
    const std::size_t end = line.find(close, i + 1);
    if (end == std::string_view::npos) return std::nullopt;
    return std::pair{std::string(line.substr(i + 1, end - i - 1)), open == '"'};
}

bool is_version(std::string_view line) {
    std::size_t i = line.find_first_not_of(" \t");
    return i != std::string_view::npos && line.substr(i, 8) == "#version";
}

struct Expander {
    const FileSource& source;
    Preprocessed out;
    std::set<std::string> seen;

    // Appends `path`'s text, whose first emitted line is `first_line` (1-based), as source string `id`.
    void expand(const std::string& path, const std::string& text, int id, int first_line) {
        const auto lines = split_lines(text);
        for (int n = first_line; n <= int(lines.size()); ++n) {
            const std::string_view line = lines[std::size_t(n - 1)];
            const auto inc = include_target(line);
            if (!inc) {
                out.text.append(line).push_back('\n');
                continue;
            }
            if (!inc->second) {   // <...>: C++ only
                out.text.push_back('\n');
                continue;
            }
            const auto dir = std::filesystem::path(path).parent_path();
            std::string target = normalise(dir / inc->first);
            std::optional<std::string> body = source.read(target);
            if (!body) {
                target = normalise(inc->first);
                body = source.read(target);
            }
            if (!body)
                throw Error("shader " + path + ":" + std::to_string(n) + ": cannot find include \"" + inc->first +
                            "\" (looked in " + source.describe() + ")");
            if (!seen.insert(target).second) {
                out.text.push_back('\n');
                continue;
            }
            const int child = int(out.files.size());
            out.files.push_back(target);
            // GLSL 4.30 §3.3: after "#line L S" the next line is line L of source string S.
            out.text += line_directive(1, child);
            expand(target, *body, child, 1);
            out.text += line_directive(n + 1, id);
        }
    }
};

}  // namespace

Preprocessed preprocess(const FileSource& source, const std::string& path, std::string_view defines) {
    const std::optional<std::string> text = source.read(path);
    if (!text) throw Error("shader " + path + ": no such file in " + source.describe());
    Expander ex{source, {}, {}};
    ex.out.files.push_back(path);
    ex.seen.insert(normalise(path));
    const auto lines = split_lines(*text);
    int version_line = 0;
    for (int n = 1; n <= int(lines.size()); ++n) {
        if (is_version(lines[std::size_t(n - 1)])) {
            version_line = n;
            break;
        }
    }
    if (!version_line) throw Error("shader " + path + ": no #version line");
    // Lines before #version can only be comments or blank; keep them so numbering stays right.
    for (int n = 1; n <= version_line; ++n) ex.out.text.append(lines[std::size_t(n - 1)]).push_back('\n');
    if (!defines.empty()) {
        ex.out.text.append(defines);
        if (defines.back() != '\n') ex.out.text.push_back('\n');
    }
    ex.out.text += line_directive(version_line + 1, 0);
    ex.expand(path, *text, 0, version_line + 1);
    return std::move(ex.out);
}

std::string annotate_log(std::string_view log, const std::vector<std::string>& files) {
    // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error C1008: ...". A line number of
    // k·kLineStride + L is line L of file k, whatever source string the driver names.
    static const std::regex mesa(R"((^|\n)(\d+):(\d+)\((\d+)\))");
    static const std::regex nvidia(R"((^|\n)(\d+)\((\d+)\) ?:)");
    auto where = [&](const std::string& id, const std::string& line) {
        std::size_t k = std::stoul(id);
        unsigned long n = std::stoul(line);
        if (n > static_cast<unsigned long>(kLineStride)) {
            k = n / kLineStride;
            n %= kLineStride;
        }
        return (k < files.size() ? files[k] : "source string " + std::to_string(k)) + ":" + std::to_string(n);
    };
    std::string text(log);
    std::string result;
    std::smatch m;
    std::string rest = text;
    while (std::regex_search(rest, m, mesa)) {
        result += m.prefix().str() + m[1].str() + where(m[2].str(), m[3].str()) + ":" + m[4].str();
        rest = m.suffix().str();
    }
    result += rest;
    text = result;
    result.clear();
    rest = text;
    while (std::regex_search(rest, m, nvidia)) {
        result += m.prefix().str() + m[1].str() + where(m[2].str(), m[3].str()) + ":";
        rest = m.suffix().str();
    }
    result += rest;
    return result;
}

}  // namespace ranryu::shader
