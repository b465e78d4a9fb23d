#!/usr/bin/env bash
# Before and after in one session: builds the bench preset of COMMIT in a scratch worktree
# (adding this tree's bench/run_bench.cpp, whose calls have the same signatures there), builds
# this tree's, then runs the benchmarks both have, alternating old and new runs REPS times, and
# prints the median time of each with the ratio new/old as a Markdown table.
# Usage: scripts/compare-benchmarks.sh COMMIT [REPS]   (e.g. 1a76ccf 5)
# The filters below pick rigid's own benchmarks (the peer engines do not change).
set -euo pipefail
commit=${1:?usage: scripts/compare-benchmarks.sh COMMIT [REPS]}
reps=${2:-5}
top=$(git rev-parse --show-toplevel)
old="${TMPDIR:-/tmp}/rigid-bench-$(git -C "$top" rev-parse --short "$commit")"
out="${TMPDIR:-/tmp}/rigid-bench-compare"
mkdir -p "$out"

"$top/scripts/install-deps.sh" bench >&2
if [[ ! -d "$old" ]]; then git -C "$top" worktree add --detach "$old" "$commit" >/dev/null; fi
cp "$top/bench/run_bench.cpp" "$old/bench/"
grep -q 'rigid_add_bench(run ' "$old/bench/CMakeLists.txt" ||
  echo 'rigid_add_bench(run LIBS rigid::scene rigid::body rigid::lagrange)' >>"$old/bench/CMakeLists.txt"
for tree in "$old" "$top"; do
  (cd "$tree" && cmake --preset bench >/dev/null && cmake --build --preset bench >/dev/null)
done

declare -A filter=(
  [body]='^BM_(Rigid/|RigidBody/|Exact|BatchRigid)'
  [lagrange]='^BM_Lagrange'
  [mesh]='^BM_Rigid'
  [run]='.'
  [sweep]='^BM_Sweep_(runs|modelRun|oneRun|perRun)'
)
rm -f "$out"/*.json
for r in $(seq 1 "$reps"); do
  for exe in body lagrange mesh run sweep; do
    for side in old new; do
      tree=$([[ $side == old ]] && echo "$old" || echo "$top")
      "$tree/build/bench/bin/rigid_${exe}_bench" --benchmark_filter="${filter[$exe]}" \
        --benchmark_min_time=0.2 --benchmark_format=json >"$out/${exe}_${side}_$r.json" 2>/dev/null
    done
  done
done

/usr/bin/python3 - "$out" "$(git -C "$top" rev-parse --short HEAD)" "$commit" <<'EOF'
import glob, json, statistics, sys
out, new_commit, old_commit = sys.argv[1:4]
times = {}
for path in glob.glob(f"{out}/*.json"):
    exe, side, _ = path.rsplit("/", 1)[1][:-5].split("_")
    for b in json.load(open(path))["benchmarks"]:
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        times.setdefault((exe, b["name"]), {}).setdefault(side, []).append(b["real_time"] * scale)
print(f"| benchmark | {old_commit} | {new_commit} | new/old |")
print("|---|---|---|---|")
def fmt(t):
    for unit, s in (("s", 1), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)):
        if t >= s:
            return f"{t / s:.3g} {unit}"
    return f"{t:.3g} s"
for (exe, name), sides in sorted(times.items()):
    if "old" not in sides or "new" not in sides:
        continue
    a, b = statistics.median(sides["old"]), statistics.median(sides["new"])
    print(f"| {exe}: {name} | {fmt(a)} | {fmt(b)} | {b / a:.3f} |")
EOF
