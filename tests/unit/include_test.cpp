// The include step (engine/shader/source.h) on in-memory trees. Every source line carries a marker
// "@file:line"; a small interpreter of GLSL 4.30 §3.3 `#line L S` (the NEXT line is line L of
// source string S) walks the preprocessed text as a driver would, and each marker's location, as
// a driver's log would give it, must come back from annotate_log() as the marker's own file and
// line. Filler line counts are random, so the line numbers differ from run to run.
#include <catch2/catch.hpp>

#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "shader/source.h"
#include "support/gl_fixture.h"   // ranryu::test::Random only; no context is made here

using ranryu::shader::annotate_log;
using ranryu::shader::FileSource;
using ranryu::shader::Preprocessed;
using ranryu::shader::preprocess;

namespace {

// Builds one file: lines are added one at a time; marked() lines carry "@path:n" for line n.
class File {
public:
    explicit File(std::string path) : path_(std::move(path)) {}
    File& line(const std::string& text) {
        text_ += text + "\n";
        ++count_;
        return *this;
    }
    File& marked(const std::string& code = "") {
        return line(code + " // @" + path_ + ":" + std::to_string(count_ + 1));
    }
    File& filler(int n) {
        for (int i = 0; i < n; ++i) marked();
        return *this;
    }
    int lines() const { return count_; }   // the number of the last line written
    std::pair<std::string, std::string> entry() const { return {path_, text_}; }

private:
    std::string path_, text_;
    int count_ = 0;
};

struct Located {
    std::size_t string_id;   // the source-string number a driver reports
    int line;                // the line number a driver reports
    std::string text;
};

// Applies `#line` as GLSL 4.30 §3.3 defines it and returns every other line with its location.
// The text starts at line 1 of source string 0.
std::vector<Located> locate(const Preprocessed& p) {
    static const std::regex directive(R"(^\s*#\s*line\s+(\d+)\s+(\d+)\s*$)");
    std::vector<Located> out;
    std::size_t string_id = 0;
    int line = 1;
    std::istringstream in(p.text);
    for (std::string text; std::getline(in, text);) {
        std::smatch m;
        if (std::regex_match(text, m, directive)) {
            line = std::stoi(m[1]);
            string_id = std::stoul(m[2]);
            continue;
        }
        out.push_back({string_id, line, text});
        ++line;
    }
    return out;
}

// Checks every "@file:line" marker in the output: where a driver that follows §3.3 puts that
// line, reported in Mesa's ("S:L(C): ...") and NVIDIA's ("S(L) : ...") log forms, annotate_log()
// must name the marker's file and line. Returns how many times each marker appeared.
std::map<std::string, int> check_markers(const Preprocessed& p) {
    static const std::regex marker(R"(@([^\s:]+):(\d+))");
    std::map<std::string, int> seen;
    for (const Located& l : locate(p)) {
        std::smatch m;
        if (!std::regex_search(l.text, m, marker)) continue;
        const std::string where = m[1].str() + ":" + m[2].str();
        const std::string S = std::to_string(l.string_id), L = std::to_string(l.line);
        INFO("output line \"" << l.text << "\" is reported as source string " << S << ", line " << L);
        CHECK(annotate_log(S + ":" + L + "(7): error: x", p.files) == where + ":7: error: x");
        CHECK(annotate_log(S + "(" + L + ") : error C0000: x", p.files) == where + ": error C0000: x");
        ++seen[where];
    }
    return seen;
}

std::string error_of(const FileSource& src, const std::string& path) {
    try {
        preprocess(src, path);
    } catch (const ranryu::Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("nested includes keep every line's file and number") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    auto n = [&] { return 1 + int(rng.below(6)); };

    // top.comp → lib/a.glsl → lib/sub/b.glsl → lib/sub/c.glsl (each relative to its includer).
    File c("lib/sub/c.glsl");
    c.filler(n());
    File b("lib/sub/b.glsl");
    b.filler(n()).line("#include \"c.glsl\"").filler(n());
    File a("lib/a.glsl");
    a.filler(n()).line("#include \"sub/b.glsl\"").filler(n());
    File top("top.comp");
    top.line("// licence header before #version").line("#version 430").filler(n());
    top.line("#include \"lib/a.glsl\"").filler(n());
    top.line("  #  include \"lib/a.glsl\"").filler(n());   // include-once: a blank line, numbering kept

    const auto src = FileSource::memory({c.entry(), b.entry(), a.entry(), top.entry()});
    const Preprocessed p = preprocess(src, "top.comp");
    INFO(p.text);
    REQUIRE(p.files.size() == 4);
    CHECK(p.files[0] == "top.comp");
    CHECK(p.files[1] == "lib/a.glsl");
    CHECK(p.files[2] == "lib/sub/b.glsl");
    CHECK(p.files[3] == "lib/sub/c.glsl");

    const auto seen = check_markers(p);
    // Every marked line of every file appears exactly once.
    std::size_t expected = 0;
    for (const File* f : {&c, &b, &a, &top}) expected += std::size_t(f->lines());
    expected -= 2 + 2 + 1 + 1;   // unmarked: top's header and #version, top's, a's and b's includes
    CHECK(seen.size() == expected);
    for (const auto& [where, count] : seen) {
        INFO(where);
        CHECK(count == 1);
    }
    CHECK(p.text.find("#include") == std::string::npos);
    // #version stays the first non-comment line, at its own line number.
    const auto located = locate(p);
    REQUIRE(located.size() >= 2);
    CHECK(located[1].text == "#version 430");
    CHECK(located[1].line == 2);
}

TEST_CASE("defines go after #version without shifting line numbers") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    File lib("lib.glsl");
    lib.filler(1 + int(rng.below(5)));
    File top("top.comp");
    top.filler(int(rng.below(3))).line("#version 430").filler(1 + int(rng.below(5)));
    top.line("#include \"lib.glsl\"").filler(2);
    const auto src = FileSource::memory({lib.entry(), top.entry()});
    const Preprocessed p = preprocess(src, "top.comp", "#define A 1\n#define B 2");
    INFO(p.text);
    check_markers(p);
    const auto a = p.text.find("#define A 1\n#define B 2\n");
    REQUIRE(a != std::string::npos);
    CHECK(p.text.find("#version 430\n") < a);
}

TEST_CASE("an include resolves against the including file first, then the root") {
    // lib/x.glsl includes "c.glsl" (lib/c.glsl exists and wins over the root's c.glsl),
    // "shared/s.h" (no lib/shared/: the root's), and "../top_only.glsl" (normalised to the root).
    File libc("lib/c.glsl");
    libc.marked("float from_lib_c;");
    File rootc("c.glsl");
    rootc.marked("float from_root_c;");
    File shared("shared/s.h");
    shared.line("#ifdef __cplusplus").line("#include <cstdint>").line("#endif").marked("float from_shared;");
    File top_only("top_only.glsl");
    top_only.marked("float from_top_only;");
    File x("lib/x.glsl");
    x.line("#include \"c.glsl\"").line("#include \"shared/s.h\"").line("#include \"../top_only.glsl\"").marked();
    File top("main.comp");
    top.line("#version 430").line("#include \"lib/x.glsl\"").line("#include \"shared/s.h\"").marked();

    const auto src = FileSource::memory({libc.entry(), rootc.entry(), shared.entry(), top_only.entry(), x.entry(), top.entry()});
    const Preprocessed p = preprocess(src, "main.comp");
    INFO(p.text);
    CHECK(p.text.find("from_lib_c") != std::string::npos);
    CHECK(p.text.find("from_root_c") == std::string::npos);
    CHECK(p.text.find("from_top_only") != std::string::npos);
    // shared/s.h is included twice (from lib/x.glsl and main.comp) and appears once.
    const auto first = p.text.find("from_shared");
    REQUIRE(first != std::string::npos);
    CHECK(p.text.find("from_shared", first + 1) == std::string::npos);
    // <...> includes belong to C++ and leave a blank line.
    CHECK(p.text.find("<cstdint>") == std::string::npos);
    CHECK(p.files == std::vector<std::string>{"main.comp", "lib/x.glsl", "lib/c.glsl", "shared/s.h", "top_only.glsl"});
    check_markers(p);
}

TEST_CASE("a file that includes itself or its includer is expanded once") {
    File a("a.glsl");
    a.line("#include \"a.glsl\"").line("#include \"top.comp\"").marked("float in_a;");
    File top("top.comp");
    top.line("#version 430").line("#include \"a.glsl\"").line("#include \"./a.glsl\"").marked();
    const Preprocessed p = preprocess(FileSource::memory({a.entry(), top.entry()}), "top.comp");
    INFO(p.text);
    CHECK(p.files == std::vector<std::string>{"top.comp", "a.glsl"});
    const auto seen = check_markers(p);
    CHECK(seen.size() == 2);
}

TEST_CASE("a missing include names the including file, its line and the missing name") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    File b("lib/b.glsl");
    b.filler(int(rng.below(7)));
    b.line("#include \"nowhere/missing.glsl\"");
    const int at = b.lines();
    File top("top.comp");
    top.line("#version 430").filler(int(rng.below(4))).line("#include \"lib/b.glsl\"");
    const std::string what = error_of(FileSource::memory({b.entry(), top.entry()}), "top.comp");
    INFO(what);
    CHECK_THAT(what, Catch::Contains("lib/b.glsl:" + std::to_string(at) + ":") &&
                         Catch::Contains("\"nowhere/missing.glsl\""));
    CHECK_THAT(what, !Catch::Contains("top.comp:"));
}

TEST_CASE("a missing file or #version line is an error naming the file") {
    const auto src = FileSource::memory({{"noversion.comp", "void main() {}\n"}});
    CHECK_THAT(error_of(src, "absent.comp"), Catch::Contains("absent.comp"));
    CHECK_THAT(error_of(src, "noversion.comp"), Catch::Contains("noversion.comp") && Catch::Contains("#version"));
}

TEST_CASE("annotate_log rewrites Mesa and NVIDIA locations to file:line") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const std::vector<std::string> files = {"sim/integrate.comp", "shared/bindings.h", "common/frame.glsl"};
    const int l0 = 1 + int(rng.below(500)), l1 = 1 + int(rng.below(500)), col = 1 + int(rng.below(80));
    const std::string L0 = std::to_string(l0), L1 = std::to_string(l1), C = std::to_string(col);

    // Mesa: "S:L(C): error: ...", one per line.
    const std::string mesa = "0:" + L0 + "(" + C + "): error: syntax error, unexpected ';'\n"
                             "1:" + L1 + "(2): warning: unused\n"
                             "2:" + L1 + "(3): error: `x' undeclared";
    const std::string m = annotate_log(mesa, files);
    INFO(m);
    CHECK(m == "sim/integrate.comp:" + L0 + ":" + C + ": error: syntax error, unexpected ';'\n"
               "shared/bindings.h:" + L1 + ":2: warning: unused\n"
               "common/frame.glsl:" + L1 + ":3: error: `x' undeclared");

    // NVIDIA: "S(L) : error Cnnnn: ...".
    const std::string nv = "1(" + L0 + ") : error C0000: syntax error, unexpected ';'\n"
                           "0(" + L1 + ") : warning C7533: deprecated";
    const std::string v = annotate_log(nv, files);
    INFO(v);
    CHECK(v == "shared/bindings.h:" + L0 + ": error C0000: syntax error, unexpected ';'\n"
               "sim/integrate.comp:" + L1 + ": warning C7533: deprecated");

    // A source string the files do not know is named as such; other text is left alone.
    CHECK(annotate_log("7:3(1): error: x", files) == "source string 7:3:1: error: x");
    CHECK(annotate_log("error: linking failed (0 of 2)", files) == "error: linking failed (0 of 2)");
}

// Mesa reports errors located at grammar nonterminals (most semantic errors) in source
// string 0 whatever `#line` said: its YYLLOC_DEFAULT sets `(Current).source = 0`
// (src/compiler/glsl/glsl_parser_extras.h; tests/gl/shader_error_test.cpp shows it on llvmpipe).
// preprocess() tells files apart by the source-string number only, so such an error in an
// included file is put in the top file. So the file is also encoded in the
// `#line` number and annotate_log() decodes it.
TEST_CASE("annotate_log finds the included file when Mesa reports source string 0") {
    File lib("lib.glsl");
    lib.filler(3);
    File top("top.comp");
    top.line("#version 430").line("#include \"lib.glsl\"").filler(3);
    const Preprocessed p = preprocess(FileSource::memory({lib.entry(), top.entry()}), "top.comp");
    static const std::regex marker(R"(@(lib\.glsl:\d+))");
    int checked = 0;
    for (const Located& l : locate(p)) {
        std::smatch m;
        if (!std::regex_search(l.text, m, marker)) continue;
        INFO(l.text);
        ++checked;
        CHECK_THAT(annotate_log("0:" + std::to_string(l.line) + "(7): error: x", p.files),
                   Catch::StartsWith(m[1].str() + ":7:"));
    }
    CHECK(checked == 3);
}
