#include "frame/stop.h"

#include <csignal>
#include <cstring>
#include <string>

namespace ranryu::frame {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop_signal(int sig) { g_signal = sig; }

}  // namespace

void stop_on_signals() {
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART | SA_RESETHAND;   // a second signal of the kind is not caught
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

std::optional<int> stop_signal() {
    const int sig = g_signal;
    return sig ? std::optional<int>(sig) : std::nullopt;
}

Error interrupted(std::uint64_t frames_run, std::uint64_t total) {
    const int sig = stop_signal().value_or(0);
    const std::string name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "signal " + std::to_string(sig);
    return Error("interrupted by " + name + " after " + std::to_string(frames_run) +
                     (total ? " of " + std::to_string(total) : std::string()) + " frames",
                 Exit::interrupted);
}

}  // namespace ranryu::frame
