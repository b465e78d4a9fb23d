#!/usr/bin/env bash
# Runs every benchmark executable of a build tree: scripts/run-benchmarks.sh build/bench
# [Google Benchmark flags], then the Python benchmarks against the module of that tree
# (bench/so3_batch_bench.py: rigid.so3 vs SciPy; bench/python_args_bench.py: the cost of an
# array argument; bench/free_bodies_python.py: step_free_bodies by steps per call), when the
# tree has the module.
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
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
modules=("$dir"/python/rigid*.so "$dir"/python/rigid/_rigid*.so)
shopt -u nullglob
if [[ ${#modules[@]} -gt 0 ]]; then
  echo "== so3_batch_bench.py"
  RIGID_PYTHON_DIR="$dir/python" /usr/bin/python3 "$root/bench/so3_batch_bench.py"
  # the per-call cost of array arguments (python/convert.hpp)
  echo "== python_args_bench.py"
  PYTHONPATH="$dir/python" /usr/bin/python3 "$root/bench/python_args_bench.py"
  # rigid.body.step_free_bodies per body-step, by steps per call
  echo "== free_bodies_python.py"
  PYTHONPATH="$dir/python" /usr/bin/python3 "$root/bench/free_bodies_python.py"
else
  echo "run-benchmarks: no Python module in $dir/python: the Python benchmarks (bench/*.py) not run" >&2
fi
