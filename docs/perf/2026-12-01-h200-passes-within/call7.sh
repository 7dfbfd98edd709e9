#!/usr/bin/env bash
# The Solve block of correct_pressure.comp alone not coherent (call 5's `nocoh`, as shipped; call 6 ran with
# the Step block of fluid.glsl not coherent too, `nocoh2`, and a GL test failed): call 6's runs again on
# this tree: the whole GL test program and the CLI profile tests on the NVIDIA driver, and the dam break at
# 246k for ten seconds against call 1's records.
exec bash "$(dirname "$0")/call6.sh"
