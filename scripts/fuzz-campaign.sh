#!/usr/bin/env bash
# A long fuzzing campaign over every reader (docs/reliability.md).
#
#   scripts/fuzz-campaign.sh [SECONDS_PER_TARGET] [TARGET...]
#
# Builds the Clang fuzz build in build/fuzz (FASTRON_FUZZ_BUILD: another folder, e.g.
# build/sanitize, which ./dev.sh test makes), then fuzzes each target (default: all) for
# SECONDS_PER_TARGET (default 420: 70 minutes over the ten readers), FASTRON_FUZZ_PARALLEL at a time
# (default: 2 on a machine with two cores or more). The corpus grows in BUILD/fuzz/corpus/NAME and
# persists between campaigns; crashing inputs land in BUILD/fuzz/findings. Writes
# BUILD/campaign.md, a table of executions, coverage and findings per target, and
# BUILD/fuzz-logs/NAME.log.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-420}
[[ $# -gt 0 ]] && shift
build=${FASTRON_FUZZ_BUILD:-build/fuzz}
scripts/install-deps.sh
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
  -DFASTRON_SANITIZE=ON -DFASTRON_FUZZ=ON -DFASTRON_NATIVE=OFF -DFASTRON_BUILD_BENCH=OFF \
  -DFASTRON_BUILD_TESTS=ON -DCMAKE_CXX_FLAGS_RELEASE=-O1 >/dev/null
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  targets=(csv path npy model urdf srdf scene moveit_scene moveit_request robot_catalogue)
fi
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/%/_fuzzer}"

fuzz=$build/fuzz
logs=$build/fuzz-logs
mkdir -p "$logs" "$fuzz/findings"
run() {  # run NAME: fuzz one target, log to $logs/NAME.log
  local name=$1 dict=()
  case $name in
    urdf | srdf) dict=(-dict=fuzz/xml.dict) ;;
    scene | moveit_* | robot_catalogue) dict=(-dict=fuzz/yaml.dict) ;;
  esac
  local inputs=(fuzz/corpus/"$name")
  [[ -d fuzz/regressions/$name ]] && inputs+=(fuzz/regressions/"$name")
  mkdir -p "$fuzz/corpus/$name"
  echo "fuzz-campaign: $name for ${seconds}s"
  export LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp
  # -fork keeps fuzzing after a finding (each one saved under findings/), as a campaign should.
  "$fuzz/${name}_fuzzer" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$fuzz/findings/$name-" "${dict[@]}" "$fuzz/corpus/$name" "${inputs[@]}" \
    >"$logs/$name.log" 2>&1 || true
}
parallel=${FASTRON_FUZZ_PARALLEL:-$(( $(nproc) >= 2 ? 2 : 1 ))}
for name in "${targets[@]}"; do
  while [[ $(jobs -rp | wc -l) -ge $parallel ]]; do wait -n; done
  run "$name" &
done
wait

{
  echo "| target | seconds | executions | exec/s | coverage (edges) | features | corpus | findings (oom + timeout + crash) |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
  for name in "${targets[@]}"; do
    log=$logs/$name.log
    # The fork mode's status lines: "#N: cov: C ft: F corp: K exec/s: E oom/timeout/crash: ...".
    last=$(grep -E '^#[0-9]+: cov:' "$log" | tail -1 || true)
    runs=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$last")
    cov=$(sed -E 's/.*cov: ([0-9]+).*/\1/' <<<"$last")
    ft=$(sed -E 's/.*ft: ([0-9]+).*/\1/' <<<"$last")
    corp=$(sed -E 's/.*corp: ([0-9]+).*/\1/' <<<"$last")
    rate=$(( ${runs:-0} / seconds ))
    # Out-of-memory inputs, timeouts and crashes (sanitizer reports, failed checks, leaks).
    found=$(sed -E 's#.*oom/timeout/crash: ([0-9]+)/([0-9]+)/([0-9]+).*#\1 + \2 + \3#' <<<"$last")
    found=$(( ${found:-0} ))
    echo "| $name | $seconds | ${runs:-?} | $rate | ${cov:-?} | ${ft:-?} | ${corp:-?} | $found |"
  done
} | tee "$build/campaign.md"
