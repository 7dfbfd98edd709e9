#pragma once
#include "cli.h"

namespace ranryu::app {
// Each returns the process exit code or throws ranryu::Error (see core/error.h).
int run(const Options& o);
int record(const Options& o);
int profile_cmd(const Options& o);
int scenes(const Options& o);
}  // namespace ranryu::app
