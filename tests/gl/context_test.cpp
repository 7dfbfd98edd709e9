#include "support/gl_fixture.h"

#include "gl/gl.h"

TEST_CASE("a headless OpenGL 4.3 core context with compute shaders") {
    const auto& info = ranryu::test::context().info();
    INFO(info.line());
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    CHECK(major * 10 + minor >= 43);
    CHECK((profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0);
    GLint groups = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &groups);
    CHECK(groups >= 65535);
    CHECK(!info.renderer.empty());
    CHECK((info.platform == "EGL device" || info.platform == "EGL surfaceless"));
    ranryu::test::require_no_gl_errors();
}
