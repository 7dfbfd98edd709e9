#include "frame/stop.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <ctime>
#include <string>

namespace ranryu::frame {
namespace {

volatile std::sig_atomic_t g_signal = 0;
// When the first signal came, in nanoseconds of CLOCK_MONOTONIC (lock-free: usable in a handler).
std::atomic<long long> g_first_ns{0};
static_assert(std::atomic<long long>::is_always_lock_free);

// The same request can arrive twice within microseconds: timeout(1) signals the command and then its
// whole process group, which holds the command too. Only a signal this long after the first is a
// second request.
constexpr long long kSecondRequestNs = 1'000'000'000;

long long monotonic_ns() {
    timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);   // async-signal-safe
    return (long long)t.tv_sec * 1'000'000'000 + t.tv_nsec;
}

extern "C" void on_stop_signal(int sig) {
    const long long now = monotonic_ns();
    if (g_signal == 0) {
        g_first_ns.store(now);
        g_signal = sig;
        return;
    }
    if (now - g_first_ns.load() < kSecondRequestNs) return;
    // A second request: end the process the default way (signal() and raise() are async-signal-safe).
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

void stop_on_signals() {
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
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
