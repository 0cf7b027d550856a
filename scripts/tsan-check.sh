#!/usr/bin/env bash
# ThreadSanitizer over the pipelined stages (the thread pool, capture's
# decoder and fit threads, the refinement stage's two threads and its
# consumer, the swap's preparation beside it, Ctrl-C): a build of core_tests
# and pipeline_tests with -fsanitize=thread in build-tsan/ (about 12 minutes
# on 2 cores the first time), then the tests that run those threads, with
# the libraries' own synchronisation suppressed (scripts/tsan.supp). Slow
# (the two swap tests take minutes each under TSan): a developer's check, not
# part of ./test.sh. Exits non-zero when a test fails or a race is reported.
# Usage: scripts/tsan-check.sh [GTEST_FILTER for pipeline_tests]
# (FACECAP_TSAN_BUILD names another build folder.)
set -euo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
cd "$top"
build=${FACECAP_TSAN_BUILD:-build-tsan}
filter=${1:-'RefineStage.*:CaptureSession.*:SwapJob.ASwapOfATargetTrackedFirstIsTheStreamedSwap:SwapJob.AHandOfTheSkinsOwnColourStaysInFront'}

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFACECAP_BENCH=OFF -DFACECAP_CUDA=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=thread -O1" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=thread" >/dev/null
cmake --build "$build" -j2 --target core_tests pipeline_tests

export TSAN_OPTIONS="halt_on_error=0 history_size=4 exitcode=66 suppressions=$top/scripts/tsan.supp"
"$build"/tests/core_tests --gtest_filter='ParallelFor*:CpuTime*:*nterrupt*:AtomicFile*'
"$build"/tests/pipeline_tests --gtest_filter="$filter"
echo "tsan-check: no data race reported"
