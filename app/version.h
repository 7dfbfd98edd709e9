#pragma once
// What `ranryu --version` prints besides the project's version (RANRYU_VERSION).
namespace ranryu::app {

// The git commit the binary was built from, "-dirty" appended when the tracked files differed from
// it, or "unknown" when it was built outside a git checkout (a tarball). Looked up at every build
// (cmake/Commit.cmake).
const char* commit();

}  // namespace ranryu::app
