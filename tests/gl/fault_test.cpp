// GPU faults (gl/faults.h): a GL error raised in a pass is reported at the frame's end with the pass's
// name; a wait on a fence that does not signal gives up after its timeout, naming what is pending.
#include "support/gl_fixture.h"

#include <chrono>

#include "gl/faults.h"
#include "gl/gl.h"
#include "gl/objects.h"
#include "profile/gpu_timer.h"

using namespace ranryu;
using Catch::Matchers::Contains;

TEST_CASE("faults: a GL error in a pass is reported with the pass that raised it", "[gl][faults]") {
    test::context();
    gl::set_error_checks(true);
    profile::GpuTimer timer(2, 8);
    const profile::PassId good = timer.pass("test.good-pass"), bad = timer.pass("test.bad-pass");
    timer.begin_frame();
    { auto pass = timer.scope(good); }
    {
        auto pass = timer.scope(bad);
        glBindBuffer(GL_ARRAY_BUFFER, 0x7FFFFFF0u);   // a name never generated: GL_INVALID_OPERATION
    }
    { auto pass = timer.scope(good); }
    timer.end_frame();
    try {
        gl::check_faults(7);
        FAIL("no fault reported");
    } catch (const gl::GpuFault& e) {
        const std::string m = e.what();
        INFO(m);
        CHECK_THAT(m, Contains("GL error 0x0502 (GL_INVALID_OPERATION) in pass test.bad-pass"));
        CHECK_THAT(m, Contains("frame 7"));
        CHECK(e.code() == Exit::failure);
    }
    CHECK_NOTHROW(gl::check_faults(8));   // reported once
    timer.drain();
    gl::set_error_checks(false);
    gl::take_gl_errors();   // the debug callback saw the provoked error too
}

TEST_CASE("faults: a fence wait gives up after its timeout and names what is pending", "[gl][faults]") {
    const auto start = std::chrono::steady_clock::now();
    try {
        gl::wait_or_fault([] { return false; }, std::chrono::milliseconds(50), "readback of frame 3");
        FAIL("waited forever");
    } catch (const gl::GpuFault& e) {
        CHECK_THAT(std::string(e.what()), Contains("GPU fence of readback of frame 3 has not signalled after 0.05 s"));
    }
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));
    // A fence that has signalled returns at once.
    test::context();
    gl::Fence f;
    f.insert();
    CHECK_NOTHROW(f.wait("test fence"));
    test::require_no_gl_errors();
}

TEST_CASE("faults: the headless context is robust where the driver allows, so a lost context reports its reset", "[gl][faults]") {
    // gl/context_egl.cpp asks EGL 1.5 for robust access with lose-context-on-reset; where that is
    // granted, glGetGraphicsResetStatus (checked at every frame's end, gl/faults.h) reports a GPU
    // reset instead of leaving the run to draw garbage. Mesa's llvmpipe and NVIDIA's driver grant it.
    ranryu::test::context();
    GLint strategy = 0, flags = 0;
    glGetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    INFO("strategy 0x" << std::hex << strategy << ", context flags 0x" << flags);
    CHECK(strategy == GL_LOSE_CONTEXT_ON_RESET);
    CHECK((flags & GL_CONTEXT_FLAG_ROBUST_ACCESS_BIT) != 0);
    CHECK(glGetGraphicsResetStatus() == GL_NO_ERROR);   // and it has not been lost
}
