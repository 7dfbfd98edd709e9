// Every reference in the sources and the docs must lead somewhere: a path named in a comment
// ("engine/sim/grid.h", "glsl/sim/fluid/*.glsl", a path relative to the engine/, glsl/, tests/ or app/
// root such as "shared/bindings.h", or a bare file name such as "force.h") must be a file or folder of
// the repository, and a section cited in a document ("docs/METHOD.md §3", "docs/SPH.md eq. (4)",
// "docs/DFSPH.md (D1)-(D8)", `docs/DFSPH.md "A step"`) must be a heading of that document: docs/METHOD.md's
// headings carry "§n", docs/SPH.md's "(n)", docs/DFSPH.md's "(Dn)", docs/PBF.md's "(Pn)", docs/SURFACE.md's "(Sn)", and a quoted citation names a
// heading's words. Inside docs/METHOD.md a bare "§n" is a section of itself.
//
// Scanned: *.cpp, *.h, *.glsl, *.comp, *.vert, *.frag (paths in comments; sections in comments and
// string literals), *.md and the bundled scenes (all their text), *.sh, *.cmake, CMakeLists.txt
// (comments). Not scanned: build folders, docs/perf (measurements), media/readme (pictures).
// A failure names the file and line of each dangling reference.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// ---- the repository as the checks see it: its files, folders and the texts of the scanned ones

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}
bool starts_with(const std::string& s, const std::string& head) { return s.rfind(head, 0) == 0; }
bool ends_with_any(const std::string& s, const std::vector<std::string>& tails) {
    return std::any_of(tails.begin(), tails.end(), [&](const std::string& t) { return ends_with(s, t); });
}

const std::vector<std::string> kCodeExtensions = {".cpp", ".h", ".glsl", ".comp", ".vert", ".frag"};
// A bare name is checked when it ends in one of these; a path with folders also when it ends in a
// data extension.
const std::vector<std::string> kSourceExtensions = {".cpp", ".h", ".glsl", ".comp", ".vert", ".frag", ".md", ".sh", ".cmake"};
const std::vector<std::string> kFileExtensions = {".cpp", ".h", ".glsl", ".comp", ".vert", ".frag", ".md", ".sh",
                                                  ".cmake", ".json", ".csv", ".txt", ".png"};
// The repository's top-level folders: a path that starts with one is relative to the root.
const std::set<std::string> kTopFolders = {"app", "engine", "glsl", "tests", "media", "scripts", "cmake", "docs", ".ci"};
// Roots that sources name paths relative to (include directories, and glsl/ for shader paths).
const std::vector<std::string> kSourceRoots = {"engine", "glsl", "tests", "app"};

enum class Syntax { none, c_like, hash, plain };

Syntax syntax_of(const std::string& rel) {
    if (starts_with(rel, "docs/perf/") || starts_with(rel, "media/readme/")) return Syntax::none;
    if (ends_with_any(rel, kCodeExtensions)) return Syntax::c_like;
    if (ends_with(rel, ".md")) return Syntax::plain;
    if (ends_with(rel, ".json") && rel.find("scenes/") != std::string::npos) return Syntax::plain;
    const std::string name = fs::path(rel).filename().string();
    if (ends_with(rel, ".sh") || ends_with(rel, ".cmake") || name == "CMakeLists.txt" || rel == ".ci/run")
        return Syntax::hash;
    return Syntax::none;
}

struct Repo {
    std::set<std::string> files, dirs, basenames;
    std::map<std::string, std::string> texts;   // the scanned files' contents

    void add(const std::string& rel, std::string text = {}) {
        files.insert(rel);
        basenames.insert(fs::path(rel).filename().string());
        for (fs::path p = fs::path(rel).parent_path(); !p.empty(); p = p.parent_path()) dirs.insert(p.generic_string());
        if (syntax_of(rel) != Syntax::none) texts[rel] = std::move(text);
    }
};

Repo read_repo(const fs::path& root) {
    Repo repo;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
        const std::string rel = fs::relative(it->path(), root).generic_string();
        const std::string name = it->path().filename().string();
        if (it->is_directory()) {
            // Not the repository's own: git's store, build and output folders, hidden tool folders.
            const bool top = it.depth() == 0;
            if (name == ".git" || (top && (starts_with(name, "build") || name == "out" || (name[0] == '.' && name != ".ci"))))
                it.disable_recursion_pending();
            continue;
        }
        if (!it->is_regular_file()) continue;
        std::string text;
        if (syntax_of(rel) != Syntax::none) {
            std::ifstream in(it->path(), std::ios::binary);
            std::ostringstream s;
            s << in.rdbuf();
            text = s.str();
        }
        repo.add(rel, std::move(text));
    }
    return repo;
}

// ---- what of a text is read: two views the length of the text, line breaks kept, all else blanked

struct Views {
    std::string comments;   // comments only: where paths are checked
    std::string prose;      // comments and string literals: where sections are checked
};

Views views_of(const std::string& text, Syntax syntax) {
    if (syntax == Syntax::plain) return {text, text};
    Views v{std::string(text.size(), ' '), std::string(text.size(), ' ')};
    auto keep = [&](std::size_t i, bool comment) {
        if (comment) v.comments[i] = text[i];
        v.prose[i] = text[i];
    };
    for (std::size_t i = 0; i < text.size(); ++i)
        if (text[i] == '\n') v.comments[i] = v.prose[i] = '\n';
    if (syntax == Syntax::hash) {
        for (std::size_t i = 0; i < text.size(); ++i) {
            if (text[i] != '#') continue;
            for (++i; i < text.size() && text[i] != '\n'; ++i) keep(i, true);
        }
        return v;
    }
    std::size_t i = 0;
    while (i < text.size()) {
        if (text.compare(i, 2, "//") == 0) {
            for (i += 2; i < text.size() && text[i] != '\n'; ++i) keep(i, true);
        } else if (text.compare(i, 2, "/*") == 0) {
            for (i += 2; i < text.size() && text.compare(i, 2, "*/") != 0; ++i)
                if (text[i] != '\n') keep(i, true);
            i += 2;
        } else if (text.compare(i, 2, "R\"") == 0 && (i == 0 || !std::isalnum(static_cast<unsigned char>(text[i - 1])))) {
            const std::size_t open = text.find('(', i + 2);
            if (open == std::string::npos) break;
            const std::string close = ")" + text.substr(i + 2, open - i - 2) + "\"";
            const std::size_t end = std::min(text.find(close, open), text.size());
            for (i = open + 1; i < end; ++i)
                if (text[i] != '\n') keep(i, false);
            i = end + close.size();
        } else if (text[i] == '"') {
            for (++i; i < text.size() && text[i] != '"' && text[i] != '\n'; ++i) {
                if (text[i] == '\\') ++i;
                else keep(i, false);
            }
            ++i;
        } else if (text[i] == '\'' && (i == 0 || !std::isalnum(static_cast<unsigned char>(text[i - 1])))) {
            for (++i; i < text.size() && text[i] != '\'' && text[i] != '\n'; ++i)
                if (text[i] == '\\') ++i;
            ++i;
        } else {
            ++i;
        }
    }
    return v;
}

struct Finding {
    std::string file;
    int line = 0;
    std::string message;
};

int line_of(const std::string& text, std::size_t pos) {
    return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(std::min(pos, text.size())), '\n'));
}

// ---- paths

bool path_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-' || c == '*' || c == '/';
}
// A path starts only after one of these is not in front of it (no tail of a URL, a longer word, $VAR/…).
bool path_glue(char c) { return path_char(c) || c == '@' || c == ':' || c == '$' || c == '~' || c == '\\' || c == '{' || c == '}'; }

// A brace group names alternatives, as in a shell: each is checked (no nesting; several groups expand
// in turn).
std::vector<std::string> expand_braces(const std::string& s) {
    const std::size_t open = s.find('{');
    if (open == std::string::npos) return {s};
    const std::size_t close = s.find('}', open);
    std::vector<std::string> out;
    std::stringstream alts(s.substr(open + 1, close - open - 1));
    for (std::string alt; std::getline(alts, alt, ',');)
        for (const auto& rest : expand_braces(s.substr(close + 1))) out.push_back(s.substr(0, open) + alt + rest);
    return out;
}

// '*' matches within one path component.
bool glob_match(const char* pattern, const char* s) {
    if (*pattern == '\0') return *s == '\0';
    if (*pattern == '*') {
        for (const char* t = s;; ++t) {
            if (glob_match(pattern + 1, t)) return true;
            if (*t == '\0' || *t == '/') return false;
        }
    }
    return *s != '\0' && *s == *pattern && glob_match(pattern + 1, s + 1);
}

bool exists_at(const Repo& repo, const std::string& path) {
    std::string p = fs::path(path).lexically_normal().generic_string();
    if (ends_with(p, "/")) p.pop_back();
    if (p.find('*') == std::string::npos) return repo.files.count(p) || repo.dirs.count(p);
    auto hit = [&](const std::string& x) { return glob_match(p.c_str(), x.c_str()); };
    return std::any_of(repo.files.begin(), repo.files.end(), hit) || std::any_of(repo.dirs.begin(), repo.dirs.end(), hit);
}

// Names that look like paths but are not the repository's, each with its reason.
struct Exemption {
    const char* file;
    const char* name;
    const char* why;
};
const Exemption kExemptions[] = {
    {"scripts/gpu/bisect-sph.sh", "glsl/sim/sph/sph_common.glsl", "the file as of the commit the script names"},
    {"scripts/gpu/bisect-sph.sh", "sph_common.glsl", "the same"},
    {"tests/unit/include_test.cpp", "*", "the shader trees the test builds in memory"},
    {"tests/gl/shader_error_test.cpp", "*", "the shader trees the test builds in memory, and Mesa's sources"},
};
bool exempt(const std::string& file, const std::string& name) {
    return std::any_of(std::begin(kExemptions), std::end(kExemptions), [&](const Exemption& e) {
        return file == e.file && (std::string(e.name) == "*" || name == e.name);
    });
}

// Where a path named in `file` may be: the root (a path from a top-level folder), else the file's own
// folder and those above it, and the source roots. A path that climbs out of a folder is looked for
// from the file's folder; where it is not there, it names something outside the repository (the scripts
// run from the root), of which nothing is said.
std::optional<bool> path_exists(const Repo& repo, const std::string& file, const std::string& path) {
    const std::string top = path.substr(0, path.find('/'));
    if (path.find('/') != std::string::npos && kTopFolders.count(top)) return exists_at(repo, path);
    const fs::path dir = fs::path(file).parent_path();
    if (starts_with(path, "../") || starts_with(path, "./")) {
        const std::string p = (dir / path).lexically_normal().generic_string();
        if (!starts_with(p, "..") && exists_at(repo, p)) return true;
        return std::nullopt;
    }
    for (fs::path d = dir;; d = d.parent_path()) {
        if (exists_at(repo, (d / path).generic_string())) return true;
        if (d.empty()) break;
    }
    return std::any_of(kSourceRoots.begin(), kSourceRoots.end(),
                       [&](const std::string& r) { return exists_at(repo, r + "/" + path); });
}

std::vector<Finding> dangling_paths(const Repo& repo, const std::string& file, const std::string& comments, int* checked) {
    std::vector<Finding> out;
    std::size_t i = 0;
    while (i < comments.size()) {
        if (!path_char(comments[i]) || (i > 0 && path_glue(comments[i - 1]))) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j < comments.size()) {
            if (path_char(comments[j])) {
                ++j;
            } else if (comments[j] == '{') {
                const std::size_t close = comments.find_first_of("}\n ", j);
                if (close == std::string::npos || comments[close] != '}') break;
                j = close + 1;
            } else {
                break;
            }
        }
        std::string token = comments.substr(i, j - i);
        const std::size_t at = i;
        i = j;
        while (!token.empty() && (token.back() == '.' || token.back() == '-' || token.back() == ',')) token.pop_back();
        if (token.empty() || token[0] == '/' || token.find("//") != std::string::npos) continue;
        const std::size_t slash = token.find('/');
        const bool folders = slash != std::string::npos && slash + 1 < token.size();
        const std::string first = token.substr(0, slash);
        bool is_path = false;
        if (folders) {
            is_path = kTopFolders.count(first) || ends_with_any(token, kFileExtensions) || starts_with(token, "../");
        } else if (slash != std::string::npos) {
            is_path = kTopFolders.count(first) > 0;   // "docs/"
        } else if (ends_with_any(token, kSourceExtensions)) {
            const std::string stem = token.substr(0, token.rfind('.'));
            is_path = std::any_of(stem.begin(), stem.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)); });
        }
        if (!is_path || exempt(file, token)) continue;
        for (const std::string& path : expand_braces(token)) {
            bool ok = true;
            if (!folders && slash == std::string::npos && path.find('*') == std::string::npos) {
                ok = repo.basenames.count(path) > 0;
            } else {
                const auto found = path_exists(repo, file, path);
                if (!found) continue;
                ok = *found;
            }
            ++*checked;
            if (!ok) out.push_back({file, line_of(comments, at), "names \"" + path + "\", which is not in the repository"});
        }
    }
    return out;
}

// ---- sections

const std::string kSection = "\xC2\xA7";               // §
const std::vector<std::string> kDashes = {"-", "\xE2\x80\x93", "\xE2\x80\x94"};   // - – —

bool doc_char(char c) { return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'; }

// The document that a document's name means, seen from `file`: the one in docs/, else the root's, else
// the one beside the file.
std::string resolve_doc(const Repo& repo, const std::string& file, const std::string& name, bool in_docs) {
    if (in_docs) return "docs/" + name;
    for (const std::string& p : {"docs/" + name, name, (fs::path(file).parent_path() / name).generic_string()})
        if (repo.files.count(p)) return p;
    return "docs/" + name;
}

// A small reader of what follows a document's name: [eq.|eqs|equations|section] ITEM (SEP ITEM)*,
// ITEM = §n | §n–§m | (n) | (Dn) | (Pn) | (n)–(m) | "heading words".
class Tail {
public:
    Tail(const std::string& s, std::size_t pos) : s_(s), p_(pos) {}

    // The cited sections: "§3", "(D4)", "\"A step\"" (ranges expanded). `quoted`: the name stood in
    // quotes, so the next quote closes them and begins no heading's words.
    std::vector<std::string> read(bool quoted = false) {
        quoted_ = quoted;
        std::vector<std::string> out;
        space();
        bool bare_numbers = false;
        for (const char* w : {"equations", "equation", "eqs.", "eqs", "eq.", "sections", "section"}) {
            if (s_.compare(p_, std::string(w).size(), w) == 0 && p_ + std::string(w).size() < s_.size() &&
                std::isspace(static_cast<unsigned char>(s_[p_ + std::string(w).size()]))) {
                bare_numbers = starts_with(w, "section");
                p_ += std::string(w).size();
                space();
                break;
            }
        }
        while (item(out, bare_numbers)) {
            const std::size_t before = p_;
            space();
            if (s_.compare(p_, 1, ",") == 0) ++p_;
            space();
            for (const char* w : {"and ", "or "})
                if (s_.compare(p_, std::string(w).size(), w) == 0) p_ += std::string(w).size();
            space();
            if (p_ == before) break;
        }
        return out;
    }

    // Where reading stopped.
    std::size_t end() const { return p_; }

private:
    bool back_to(std::size_t pos) {
        p_ = pos;
        return false;
    }
    void space() {
        while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
    }
    bool literal(const std::string& w) {
        if (s_.compare(p_, w.size(), w) != 0) return false;
        p_ += w.size();
        return true;
    }
    bool dash() {
        const std::size_t keep = p_;
        space();
        for (const auto& d : kDashes)
            if (literal(d)) {
                space();
                return true;
            }
        p_ = keep;
        return false;
    }
    std::string digits() {
        const std::size_t b = p_;
        while (p_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p_]))) ++p_;
        return s_.substr(b, p_ - b);
    }
    bool item(std::vector<std::string>& out, bool bare_numbers) {
        const std::size_t start = p_;
        if (literal(kSection) || (bare_numbers && p_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p_])))) {
            const std::string a = digits();
            if (a.empty()) return back_to(start);
            std::string b = a;
            const std::size_t keep = p_;
            if (dash()) {
                literal(kSection);
                b = digits();
                if (b.empty()) {
                    p_ = keep;
                    b = a;
                }
            }
            for (int n = std::stoi(a); n <= std::max(std::stoi(a), std::stoi(b)); ++n) out.push_back(kSection + std::to_string(n));
            return true;
        }
        if (literal("(")) {
            const std::string prefix = literal("D") ? "D" : literal("P") ? "P" : literal("S") ? "S" : "";
            const std::string a = digits();
            if (a.empty() || !literal(")")) return back_to(start);
            std::string b = a;
            const std::size_t keep = p_;
            if (dash() && literal("(" + prefix)) {
                b = digits();
                if (b.empty() || !literal(")")) b.clear();
            }
            if (b.empty()) {
                p_ = keep;
                b = a;
            }
            for (int n = std::stoi(a); n <= std::max(std::stoi(a), std::stoi(b)); ++n)
                out.push_back("(" + prefix + std::to_string(n) + ")");
            return true;
        }
        if (!quoted_ && literal("\"")) {
            const std::size_t end = s_.find_first_of("\"\n", p_);
            if (end == std::string::npos || s_[end] != '"' || end == p_) return back_to(start);
            out.push_back(s_.substr(p_ - 1, end - p_ + 2));
            p_ = end + 1;
            return true;
        }
        return false;
    }

    const std::string& s_;
    std::size_t p_;
    bool quoted_ = false;
};

std::vector<std::string> headings(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (starts_with(line, "#")) out.push_back(line);
    return out;
}

// Whether `doc` has the section `cited` ("§3", "(D4)" or "\"words\"").
bool has_section(const std::string& doc, const std::string& cited) {
    for (const std::string& h : headings(doc)) {
        if (cited[0] == '"') {
            if (h.find(cited.substr(1, cited.size() - 2)) != std::string::npos) return true;
            continue;
        }
        for (std::size_t at = h.find(cited); at != std::string::npos; at = h.find(cited, at + 1)) {
            const std::size_t end = at + cited.size();
            if (end >= h.size() || !std::isdigit(static_cast<unsigned char>(h[end]))) return true;
        }
    }
    return false;
}

std::vector<Finding> dangling_sections(const Repo& repo, const std::string& file, const std::string& prose, int* checked) {
    std::vector<Finding> out;
    auto check = [&](const std::string& doc, std::size_t at, const std::vector<std::string>& cited) {
        const auto text = repo.texts.find(doc);
        for (const std::string& c : cited) {
            ++*checked;
            if (text == repo.texts.end())
                out.push_back({file, line_of(prose, at), "cites " + doc + " " + c + ", and there is no " + doc});
            else if (!has_section(text->second, c))
                out.push_back({file, line_of(prose, at), "cites " + doc + " " + c + ", which is no heading of " + doc});
        }
    };
    for (std::size_t md = prose.find(".md"); md != std::string::npos; md = prose.find(".md", md + 1)) {
        std::size_t b = md;
        while (b > 0 && doc_char(prose[b - 1])) --b;
        if (b == md || !std::isupper(static_cast<unsigned char>(prose[b]))) continue;
        const bool in_docs = b >= 5 && prose.compare(b - 5, 5, "docs/") == 0;
        const std::size_t start = in_docs ? b - 5 : b;
        if (start > 0 && path_glue(prose[start - 1])) continue;
        const std::size_t end = md + 3;
        if (end < prose.size() && path_char(prose[end]) && prose[end] != '.') continue;
        const std::string doc = resolve_doc(repo, file, prose.substr(b, end - b), in_docs);
        check(doc, start, Tail(prose, end).read(start > 0 && prose[start - 1] == '"'));
    }
    if (file == "docs/METHOD.md") {   // its own "§n"
        for (std::size_t s = prose.find(kSection); s != std::string::npos; s = prose.find(kSection, s + 1)) {
            Tail tail(prose, s);
            check(file, s, tail.read());
            s = std::max(tail.end(), s + kSection.size()) - 1;   // past what was read: "§3–§6" is not read again from "§6"
        }
    }
    return out;
}

std::string report(const std::vector<Finding>& findings) {
    std::string r;
    for (const auto& f : findings) r += f.file + ":" + std::to_string(f.line) + ": " + f.message + "\n";
    return r;
}

// Runs both checks over every scanned file of `repo`.
std::vector<Finding> check_repo(const Repo& repo, int* paths, int* sections) {
    std::vector<Finding> all;
    for (const auto& [file, text] : repo.texts) {
        Views v = views_of(text, syntax_of(file));
        // This file's string literals are the fixtures below, made to fail on purpose.
        if (file == "tests/unit/doc_references_test.cpp") v.prose = v.comments;
        for (auto& f : dangling_paths(repo, file, v.comments, paths)) all.push_back(std::move(f));
        for (auto& f : dangling_sections(repo, file, v.prose, sections)) all.push_back(std::move(f));
    }
    return all;
}

Repo fixture() {
    Repo r;
    r.add("docs/METHOD.md", "# M\n## §1 One\nsee §1 and §1–§2\n## §2 Two\n");
    r.add("docs/SPH.md", "# S\n## (1) Kernel\n## (2) Density\n");
    r.add("docs/DFSPH.md", "# D\n## (D1) Rate\n## A step\n");
    r.add("engine/sim/grid.h");
    r.add("glsl/shared/bindings.h");
    r.add("glsl/sim/fluid/fluid.glsl");
    return r;
}

}  // namespace

TEST_CASE("doc references: the checks find what dangles, and only that", "[doc-references]") {
    Repo r = fixture();
    r.add("engine/good.cpp",
          "// docs/METHOD.md §1, METHOD.md §1–§2, docs/SPH.md eq. (1), docs/SPH.md (1)-(2), docs/DFSPH.md (D1),\n"
          "// docs/DFSPH.md \"A step\"; engine/sim/grid.h, shared/bindings.h, glsl/sim/fluid/*.glsl, grid.h,\n"
          "// glsl/{sim,shared}/ the folders; https://example.org/a/b.h; ../../outside/x.h; GLSL 4.30 §3.3;\n"
          "// \"METHOD.md\" or \"SPH.md\" by name\n"
          "const char* s = R\"(docs/METHOD.md\n"
          "section 2)\";\n");
    r.add("engine/bad.cpp",
          "int x;\n"
          "// METHOD.md §3, docs/SPH.md (1)–(3), docs/DFSPH.md \"Nowhere\", docs/NONE.md §1\n"
          "/* engine/sim/gone.h, surface/bounds.glsl,\n"
          "   missing.glsl, tests/data/scenes/a-{b,c}.json */\n"
          "const char* s = R\"(docs/SPH.md eqs (9))\";\n");
    int paths = 0, sections = 0;
    const auto good = [&] {
        std::vector<Finding> f;
        const Views v = views_of(r.texts.at("engine/good.cpp"), Syntax::c_like);
        for (auto& x : dangling_paths(r, "engine/good.cpp", v.comments, &paths)) f.push_back(x);
        for (auto& x : dangling_sections(r, "engine/good.cpp", v.prose, &sections)) f.push_back(x);
        for (auto& x : dangling_sections(r, "docs/METHOD.md", r.texts.at("docs/METHOD.md"), &sections)) f.push_back(x);
        return f;
    }();
    INFO(report(good));
    CHECK(good.empty());
    CHECK(paths == 14);          // 6 names of documents, 8 other paths (the braces name 2)
    CHECK(sections == 9 + 5);    // the good file's, and the fixture METHOD.md's own

    const Views v = views_of(r.texts.at("engine/bad.cpp"), Syntax::c_like);
    std::vector<Finding> bad = dangling_paths(r, "engine/bad.cpp", v.comments, &paths);
    for (auto& x : dangling_sections(r, "engine/bad.cpp", v.prose, &sections)) bad.push_back(x);
    const std::string got = report(bad);
    INFO(got);
    CHECK(got.find("engine/bad.cpp:3: names \"engine/sim/gone.h\"") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:3: names \"surface/bounds.glsl\"") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:4: names \"missing.glsl\"") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:4: names \"tests/data/scenes/a-b.json\"") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:4: names \"tests/data/scenes/a-c.json\"") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:2: cites docs/METHOD.md §3, which is no heading") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:2: cites docs/SPH.md (3), which is no heading") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:2: cites docs/DFSPH.md \"Nowhere\"") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:2: cites docs/NONE.md §1, and there is no docs/NONE.md") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:5: cites docs/SPH.md (9)") != std::string::npos);
    CHECK(got.find("engine/bad.cpp:2: names \"docs/NONE.md\"") != std::string::npos);
    CHECK(bad.size() == 11);
}

TEST_CASE("doc references: every file and section that the sources and docs name exists", "[doc-references]") {
    const Repo repo = read_repo(RANRYU_SOURCE_DIR);
    REQUIRE(repo.texts.count("docs/METHOD.md"));
    int paths = 0, sections = 0;
    const auto findings = check_repo(repo, &paths, &sections);
    // Guards against a scan that reads nothing: the tree holds hundreds of each.
    CHECK(repo.texts.size() > 150);
    CHECK(paths > 300);
    CHECK(sections > 100);
    for (const auto& f : findings) FAIL_CHECK(f.file << ":" << f.line << ": " << f.message);
}
