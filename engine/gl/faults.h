#pragma once
// GPU faults (issue 15, item 8): a GL error raised in a pass, a lost context, or a fence that has not
// signalled in time ends the run with exit 1 and a message naming the pass, instead of drawing
// garbage or waiting forever.
//
//     set_error_checks(true)   Debug builds and --gl-debug: glGetError after every timed pass
//                              (profile::GpuTimer::Scope), kept out of release frame paths
//     check_faults(frame)      frame end: throws GpuFault for the first GL error seen, or when
//                              glGetGraphicsResetStatus reports the context lost
//     wait_or_fault(...)       the waits of drains and back-pressure: at most fence_timeout_seconds()
//                              (10 s, RANRYU_FENCE_TIMEOUT_SECONDS), then GpuFault naming what is pending
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/error.h"

namespace ranryu::gl {

class GpuFault : public Error {
public:
    explicit GpuFault(const std::string& what) : Error(what, Exit::failure) {}
};

void set_error_checks(bool on);
bool error_checks();

// The pass being recorded (profile::GpuTimer::Scope sets it), for the messages; "" outside passes.
void set_current_pass(const std::string& name);
const std::string& current_pass();

// With error checks on: glGetError, and any error is kept, named with `pass`, for check_faults().
void check_gl_error(const std::string& pass);
// The first fault kept since the last call, if any (tests).
std::optional<std::string> take_fault();
// Throws GpuFault for a kept GL error, or for a lost context (robust contexts report it).
void check_faults(std::uint64_t frame);

double fence_timeout_seconds();   // RANRYU_FENCE_TIMEOUT_SECONDS, else 10

// Calls `signaled` until it returns true, for at most `timeout`; then throws GpuFault: "`what` has not
// signalled after N s".
void wait_or_fault(const std::function<bool()>& signaled, std::chrono::duration<double> timeout, const std::string& what);

}  // namespace ranryu::gl
