#!/usr/bin/env bash
# Fastron's one entry point for people and CI. Each command installs the missing Debian
# packages first (scripts/install-deps.sh), then builds what it needs.
#
#   ./dev.sh demo [ARGS]   build Release and run `fastron demo ARGS`
#   ./dev.sh test          build and run the whole test suite: Release; then a Clang build with
#                          address+undefined sanitizers that runs the tests and fuzzes every
#                          reader for FASTRON_FUZZ_SECONDS (default 10) each; then
#                          ThreadSanitizer on the concurrency and soak tests
#   ./dev.sh build         build Release into build/release
#   ./dev.sh bench [ARGS]  build Release and run the Google Benchmark micro-benchmarks
#   ./dev.sh format        reformat every source file with clang-format
#   ./dev.sh tidy          run clang-tidy over the library sources
set -euo pipefail
cd "$(dirname "$0")"
jobs=$(nproc)

build() {  # build DIR BUILD_TYPE [CMAKE ARGS...] [--target T...]
  local dir=$1 type=$2 configure=() targets=()
  shift 2
  while [[ $# -gt 0 && $1 != --target ]]; do configure+=("$1"); shift; done
  [[ $# -gt 0 ]] && targets=("$@")
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE="$type" "${configure[@]}" >/dev/null
  cmake --build "$dir" -j "$jobs" "${targets[@]}"
}

command=${1:-}
[[ $# -gt 0 ]] && shift
case "$command" in
  demo)
    scripts/install-deps.sh
    build build/release Release
    build/release/apps/fastron/fastron demo "$@"
    ;;
  test)
    scripts/install-deps.sh
    build build/release Release
    ctest --test-dir build/release --output-on-failure -j "$jobs"
    # Sanitizer builds at -O1 without debug info, as unity builds (several sources per
    # compiler run; the SIMD paths' files, which carry their own flags, stay apart): they compile
    # in a fraction of the time, and the reports still name every function. The address+undefined
    # build is Clang's, with the fuzz targets (fuzz/): one build of the library serves the tests
    # and the fuzzers.
    build build/sanitize Release -DCMAKE_CXX_COMPILER=clang++ -DFASTRON_SANITIZE=ON -DFASTRON_FUZZ=ON \
      -DFASTRON_FUZZ_SECONDS="${FASTRON_FUZZ_SECONDS:-10}" -DFASTRON_NATIVE=OFF \
      -DFASTRON_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS_RELEASE=-O1 -DCMAKE_UNITY_BUILD=ON
    ctest --test-dir build/sanitize --output-on-failure -j "$jobs" -LE no-sanitizer
    build build/tsan Release -DFASTRON_TSAN=ON -DFASTRON_NATIVE=OFF -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
      -DCMAKE_UNITY_BUILD=ON --target core_concurrency_tests proxy_tests proxy_soak \
      planning_concurrency_tests geometry_concurrency_tests
    ctest --test-dir build/tsan --output-on-failure -j "$jobs" -L concurrency
    ;;
  build)
    scripts/install-deps.sh
    build build/release Release
    ;;
  bench)
    scripts/install-deps.sh
    build build/release Release
    build/release/bench/fastron_bench "$@"
    ;;
  format)
    git ls-files '*.h' '*.cpp' | xargs clang-format -i
    ;;
  tidy)
    scripts/install-deps.sh
    build build/release Release
    git ls-files 'src/*.cpp' | xargs clang-tidy -p build/release --quiet
    ;;
  *)
    awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"
    exit 2
    ;;
esac
