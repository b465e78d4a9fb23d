#!/usr/bin/env bash
# Runs every fuzz target of a `fuzz` build for N seconds each, from a fresh seed corpus
# (fuzz/make_seeds.py) plus the corpus kept from earlier runs and the saved reproducers.
# Usage: [RIGID_FUZZ_JOBS=J] scripts/run-fuzz.sh BUILD_DIR SECONDS [TARGET...]
# J targets run at once (default 1; each is one libFuzzer worker and its parent), in the order
# of fuzz/targets.def. Findings (crash-*, timeout-*, oom-*, leak-*) land in
# BUILD_DIR/fuzz-findings/<target>/ with the target's log beside them; the summary at the end
# gives each target's inputs run and lists the findings, and the exit status is 1 when there
# are any.
# Limits: an input running longer than 10 s is a hang, one using more than 2 GB is out of
# memory; inputs are at most 8 KiB (the largest seed is 4 KiB).
set -uo pipefail
build=${1:?usage: run-fuzz.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: run-fuzz.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  mapfile -t targets < <(sed -n 's/^RIGID_FUZZ_TARGET(\(.*\))$/\1/p' "$root/fuzz/targets.def")
fi

jobs=${RIGID_FUZZ_JOBS:-1}
[[ $jobs =~ ^[1-9][0-9]*$ ]] || { echo "run-fuzz: RIGID_FUZZ_JOBS=$jobs, expected a count of at least 1" >&2; exit 2; }
for t in "${targets[@]}"; do
  [[ -x $build/bin/rigid_fuzz_$t ]] || { echo "run-fuzz: $build/bin/rigid_fuzz_$t is not built" >&2; exit 2; }
done

rm -rf "$build/fuzz-seeds"
/usr/bin/python3 "$root/fuzz/make_seeds.py" "$build/fuzz-seeds" >/dev/null
status=0

# one target: its corpus, seeds and reproducers, its own scratch directory (the mesh targets'
# files), removed after
fuzz_one() {
  local t=$1
  local tmp="$build/fuzz-tmp/$t"
  mkdir -p "$build/fuzz-corpus/$t" "$build/fuzz-findings/$t" "$tmp"
  local dirs=("$build/fuzz-corpus/$t" "$build/fuzz-seeds/$t")
  [[ -d $root/fuzz/regressions/$t ]] && dirs+=("$root/fuzz/regressions/$t")
  # -fork=1 with -ignore_*: keep fuzzing after a finding, so one run reports every kind
  TMPDIR="$tmp" ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1 \
  LSAN_OPTIONS=suppressions="$root/fuzz/lsan.supp":print_suppressions=0 \
    "$build/bin/rigid_fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -max_len=8192 -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -artifact_prefix="$build/fuzz-findings/$t/" "${dirs[@]}" >"$build/fuzz-findings/$t.log" 2>&1
  rm -rf "$tmp"
  echo "== $t: ${seconds} s done"
}

running=0
for t in "${targets[@]}"; do
  if (( running >= jobs )); then
    wait -n
    running=$((running - 1))
  fi
  echo "== $t: ${seconds} s"
  fuzz_one "$t" &
  running=$((running + 1))
done
wait

echo "== inputs run"
for t in "${targets[@]}"; do
  # fork mode's last status line: "#N: cov: … exec/s: … oom/timeout/crash: …"
  last=$(grep -E '^#[0-9]+: cov' "$build/fuzz-findings/$t.log" | tail -n 1)
  echo "$t: ${last:-no status line (see $build/fuzz-findings/$t.log)}"
done

echo "== findings"
for t in "${targets[@]}"; do
  found=$(find "$build/fuzz-findings/$t" -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \) | sort)
  if [[ -n $found ]]; then
    status=1
    echo "$t:"; echo "$found" | sed 's/^/  /'
  else
    echo "$t: none"
  fi
done
exit $status
