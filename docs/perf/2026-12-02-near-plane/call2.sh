#!/usr/bin/env bash
# Call 2 (2026-12-02, night): the three test programs on the H200 with the session's tree (the unit and
# CLI programs last ran here on 2026-11-30 with 270b501; the GL program in call 1). Run on 1a9eaf3.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
OUT=$OUT scripts/gpu/tests.sh
