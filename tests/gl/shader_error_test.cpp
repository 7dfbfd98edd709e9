// Compile errors on a real driver name the file and line the author wrote. This holds only if the
// `#line L S` directives that preprocess() emits mean what GLSL 4.30 §3.3 says (the line after the
// directive is line L of source string S) on this driver, and annotate_log() reads its log form.
// The error sits at a random line each run.
#include "support/gl_fixture.h"

#include <regex>
#include <string>

#include "core/error.h"
#include "gl/gl.h"
#include "shader/program.h"

using ranryu::shader::FileSource;
using ranryu::shader::Program;

namespace {

std::string filler(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += "// filler\n";
    return s;
}

// The message of the ranryu::Error that building the compute program `path` raises ("" if none).
// A failed compile also reaches the debug callback as GL_DEBUG_TYPE_ERROR messages from the
// shader compiler; those are taken here, and each must be a compiler diagnostic ("S:L(C): error"
// on Mesa, "S(L) : error" on NVIDIA), so an API error in the same call still fails the case.
std::string compile_error(const FileSource& src, const std::string& path, std::string_view defines = {}) {
    std::string what;
    try {
        Program::compute(src, path, defines);
    } catch (const ranryu::Error& e) {
        what = e.what();
    }
    static const std::regex diagnostic(R"(\d+(:\d+\(\d+\)|\(\d+\) ?):)");
    for (const std::string& e : ranryu::gl::take_gl_errors()) {
        INFO("debug message: " << e);
        CHECK(std::regex_search(e, diagnostic));
    }
    return what;
}

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

// A GLSL file whose line `line` is the first line of `body` (comment lines before it).
std::string at_line(int line, const std::string& body) { return filler(line - 1) + body; }

const std::string kSyntaxError = "float broken = ;\n";
const std::string kLib = "float lib_value() { return 1.0; }\n";

}  // namespace

TEST_CASE("a syntax error in an included file is reported at that file and line") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // top.comp includes lib/a.glsl, which includes lib/b.glsl, which has the error at line `bad`.
    const int bad = 2 + int(rng.below(20));
    const auto src = FileSource::memory({
        {"top.comp", "#version 430\n" + filler(int(rng.below(5))) + "#include \"lib/a.glsl\"\n" + filler(3) +
                         "layout(local_size_x = 1) in;\nvoid main() {}\n"},
        {"lib/a.glsl", filler(int(rng.below(5))) + "#include \"b.glsl\"\n" + kLib},
        {"lib/b.glsl", at_line(bad, kSyntaxError)},
    });
    const std::string what = compile_error(src, "top.comp");
    INFO("bad line " << bad << "; message:\n" << what);
    REQUIRE(!what.empty());
    CHECK_THAT(first_line(what), Catch::StartsWith("shader lib/b.glsl:" + std::to_string(bad) + ":"));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("a syntax error after an include is reported at the including file's own line") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // The include's body is several lines long, so a #line that failed to restore the top file's
    // numbering after it would be off by that many.
    const int include_at = 2 + int(rng.below(6));
    const int bad = include_at + 1 + int(rng.below(10));
    const std::string top = "#version 430\n" + filler(include_at - 2) + "#include \"lib/long.glsl\"\n" +
                            filler(bad - include_at - 1) + kSyntaxError +
                            "layout(local_size_x = 1) in;\nvoid main() {}\n";
    const auto src = FileSource::memory({
        {"top.comp", top},
        {"lib/long.glsl", filler(1 + int(rng.below(30))) + kLib},
    });
    SECTION("without defines") {
        const std::string what = compile_error(src, "top.comp");
        INFO("bad line " << bad << "; message:\n" << what);
        CHECK_THAT(first_line(what), Catch::StartsWith("shader top.comp:" + std::to_string(bad) + ":"));
    }
    SECTION("with defines inserted after #version") {
        const std::string what = compile_error(src, "top.comp", "#define RANRYU_A 1\n#define RANRYU_B 2\n");
        INFO("bad line " << bad << "; message:\n" << what);
        CHECK_THAT(first_line(what), Catch::StartsWith("shader top.comp:" + std::to_string(bad) + ":"));
    }
    ranryu::test::require_no_gl_errors();
}

namespace {
// An undeclared name at line `bad` of common/x.glsl, included from top.comp at line 2.
FileSource semantic_error_tree(int bad) {
    return FileSource::memory({
        {"top.comp", "#version 430\n#include \"common/x.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n"},
        {"common/x.glsl", at_line(bad, "float f() { return undeclared_name; }\n")},
    });
}
}  // namespace

TEST_CASE("a semantic error in an included file is reported at its line") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const int bad = 3 + int(rng.below(20));   // never line 2, where top.comp has its include
    const std::string what = compile_error(semantic_error_tree(bad), "top.comp");
    INFO("bad line " << bad << "; message:\n" << what);
    CHECK_THAT(first_line(what), Catch::StartsWith("shader ") && Catch::Contains(":" + std::to_string(bad) + ": ") &&
                                     Catch::Contains("undeclared_name"));
    ranryu::test::require_no_gl_errors();
}

// Mesa reports errors located at grammar nonterminals (most semantic errors, this one
// included) in source string 0, with the right line: its YYLLOC_DEFAULT sets `(Current).source = 0`
// (src/compiler/glsl/glsl_parser_extras.h). preprocess() tells files apart by the source-string
// number only, so on Mesa the message names top.comp. The engine therefore encodes
// the file in the #line number (engine/shader/source.cpp).
TEST_CASE("a semantic error in an included file names that file") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const int bad = 3 + int(rng.below(20));
    const std::string what = compile_error(semantic_error_tree(bad), "top.comp");
    INFO("bad line " << bad << "; message:\n" << what);
    CHECK_THAT(first_line(what), Catch::StartsWith("shader common/x.glsl:" + std::to_string(bad) + ":"));
    ranryu::test::require_no_gl_errors();
}
