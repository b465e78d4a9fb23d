#!/usr/bin/env bash
# Runs pytest on the given directories as two processes at once, so that both cores of a
# two-core machine work (a test mostly waits on one `rigid` process or one Python thread).
# The test files are split by the seconds each took in a recorded run
# (scripts/pytest-seconds.txt; a file not listed counts 1 s), the longest first, each to the
# shard with less so far. Each shard's output is printed when both are done; the exit status
# is the first failing shard's.
#   usage: scripts/run-pytest.sh PYTHON DIR...
set -euo pipefail
python=$1
shift
here=$(cd "$(dirname "$0")" && pwd)
mapfile -t files < <(find "$@" -name 'test_*.py' | sort)
mapfile -t shards < <(awk -v n=2 '
  FNR == NR { seconds[$1] = $2; next }
  { w = ($1 in seconds) ? seconds[$1] : 1; print w, $1 }' \
  "$here/pytest-seconds.txt" <(printf '%s\n' "${files[@]}") |
  sort -k1,1gr -k2,2 |
  awk '{ k = (load[0] <= load[1]) ? 0 : 1; load[k] += $1; list[k] = list[k] " " $2 }
       END { print list[0]; print list[1] }')
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# A shell without job control starts `&` commands with SIGINT ignored, and Python then never
# raises KeyboardInterrupt (nor do the processes it starts see SIGINT): each shard puts Python's
# own handler back before pytest starts, for the tests of Ctrl-C.
run_shard='import signal, sys, pytest
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.exit(pytest.main(sys.argv[1:]))'
pids=()
for k in 0 1; do
  # shellcheck disable=SC2086 # the file list is split on purpose
  "$python" -c "$run_shard" -q -p no:cacheprovider ${shards[$k]} >"$out/$k.log" 2>&1 &
  pids+=($!)
done
status=0
for k in 0 1; do
  rc=0
  wait "${pids[$k]}" || rc=$?
  echo "=== pytest shard $((k + 1)) of 2 (exit $rc)"
  cat "$out/$k.log"
  if [ "$status" -eq 0 ] && [ "$rc" -ne 0 ]; then status=$rc; fi
done
exit "$status"
