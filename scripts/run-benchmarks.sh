#!/usr/bin/env bash
# Runs every benchmark executable of a build tree: scripts/run-benchmarks.sh build/bench
set -euo pipefail
dir="${1:-build/bench}"
shopt -s nullglob
exes=("$dir"/bin/*_bench)
if [[ ${#exes[@]} -eq 0 ]]; then
  echo "run-benchmarks: no *_bench executables in $dir/bin (build the bench preset first)" >&2
  exit 1
fi
for exe in "${exes[@]}"; do
  echo "== $(basename "$exe")"
  "$exe" --benchmark_min_time=0.2 "${@:2}"
done
# the Python module's per-call cost of array arguments (python/convert.hpp)
if [[ -d "$dir/python" ]]; then
  echo "== python_args_bench.py"
  PYTHONPATH="$dir/python" /usr/bin/python3 "$(dirname "$0")/../bench/python_args_bench.py"
fi
