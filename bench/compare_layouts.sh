#!/usr/bin/env bash
# Does the cycle's speed depend on where the build lives? Builds the same commit in two clone
# folders whose paths differ in length (the executables then differ only in the paths they embed),
# times `comply bench` in each, alternating A B A B, and compares the full-cycle p50 of every
# wrapper. Exit 1 when a wrapper differs by more than TOLERANCE_PERCENT (default 3).
#
#   bench/compare_layouts.sh [COMMIT] [ROBOT]          (defaults: HEAD, fr3)
#
# ccache, with its base directory set to each clone, compiles the second clone from the first's
# objects. Keeps the clones under ${LAYOUT_DIR:-/tmp/comply-layouts} for a second look.
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/.." && pwd)
commit=${1:-HEAD}
robot=${2:-fr3}
tolerance=${TOLERANCE_PERCENT:-3}
root=${LAYOUT_DIR:-/tmp/comply-layouts}
python=/usr/bin/python3
folders=("$root/a" "$root/a_much_longer_folder_name_that_moves_every_embedded_path")

mkdir -p "$root"
for folder in "${folders[@]}"; do
  if [ ! -d "$folder/.git" ]; then
    git clone --quiet --shared "$source_dir" "$folder"
  fi
  git -C "$folder" checkout --quiet --detach "$(git -C "$source_dir" rev-parse "$commit")"
  echo "building $folder" >&2
  CCACHE_BASEDIR="$folder" cmake -S "$folder" -B "$folder/build" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCOMPLY_BUILD_TESTS=OFF >/dev/null
  CCACHE_BASEDIR="$folder" cmake --build "$folder/build" --target comply \
    comply_cartesian_impedance comply_joint_impedance >/dev/null
done

run() {  # $1: folder, $2: output file
  "$1/build/apps/comply/comply" bench --robot "$robot" --processes 5 --json >"$2"
}
for round in 1 2; do
  for index in 0 1; do
    echo "round $round: ${folders[$index]}" >&2
    run "${folders[$index]}" "$root/bench_${index}_${round}.json"
  done
done

"$python" - "$root" "$tolerance" <<'EOF'
import json
import sys

root, tolerance = sys.argv[1], float(sys.argv[2])
p50 = [{}, {}]
for index in (0, 1):
    for round_ in (1, 2):
        with open(f"{root}/bench_{index}_{round_}.json") as handle:
            for row in json.load(handle)["rows"]:
                if row["stage"] == "full_cycle":
                    p50[index].setdefault(row["wrapper"], []).append(row["p50_us"])
worst = 0.0
print(f"{'wrapper':20s} {'folder a p50 [us]':>18s} {'folder b p50 [us]':>18s} {'b / a':>8s}")
for wrapper, a in p50[0].items():
    b = p50[1][wrapper]
    mean_a, mean_b = sum(a) / len(a), sum(b) / len(b)
    change = 100.0 * (mean_b / mean_a - 1.0)
    worst = max(worst, abs(change))
    print(f"{wrapper:20s} {mean_a:18.3f} {mean_b:18.3f} {change:+7.1f}%")
print(f"largest difference {worst:.1f}% (tolerance {tolerance:g}%)")
sys.exit(0 if worst <= tolerance else 1)
EOF
