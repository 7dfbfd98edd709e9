#pragma once
// Errors carry the process exit code the app reports (README: 0 ok, 1 failure, 2 bad input,
// 3 unstable simulation, 130 interrupted by SIGINT or SIGTERM: frame/stop.h), so the app has one
// catch site and one message line per failure.
#include <stdexcept>
#include <string>

namespace ranryu {

enum class Exit : int { ok = 0, failure = 1, bad_input = 2, unstable = 3, interrupted = 130 };

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& what, Exit code = Exit::failure)
        : std::runtime_error(what), code_(code) {}
    Exit code() const { return code_; }

private:
    Exit code_;
};

// Bad input from the user: usage, scene file, parameter, output folder. Exit code 2.
class InputError : public Error {
public:
    explicit InputError(const std::string& what) : Error(what, Exit::bad_input) {}
};

}  // namespace ranryu
