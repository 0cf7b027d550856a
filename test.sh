#!/usr/bin/env bash
# Runs the whole GoogleTest suite (after ./setup.sh).
set -euo pipefail
cd "$(dirname "$0")"
[ -x build/facecap ] || { echo "test.sh: build/ is missing: run ./setup.sh first" >&2; exit 1; }
exec ctest --test-dir build --output-on-failure -j2 "$@"
