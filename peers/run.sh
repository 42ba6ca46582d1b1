#!/usr/bin/env bash
# The whole peer comparison behind BENCHMARKS.md, in one run on one machine:
#   1. Embree (embree_anchor.py): its build time and Mrays/s on its meshes and rays;
#   2. raylab's BVH, the `bvh` crate and `obvhs` on the same dumped meshes and rays (raylab-peers);
#   3. POV-Ray 3.7 against `raylab render` on the seven SPD standard scenes, 512x512, depth 5,
#      no anti-aliasing, 2 threads, the two by turns: whole-process wall time, and POV's own
#      trace time against raylab's render time;
#   4. `raylab bench --scaling` (the standard set, 2 threads) for the figures of raylab alone.
#
# usage: peers/run.sh [OUT_DIR=/tmp/raylab-peers] [RUNS=5]
#   env: SHARED  the measurement tools and scenes (default: ../shared beside the repository).
#                They are not part of this repository; this script stops when they are missing.
#        SKIP    any of embree,crates,povray,bench to leave out, comma-separated.
# Needs: python3 with embreex and numpy (pip), povray (Debian package), cargo.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SHARED:-$root/../shared}
out=${1:-/tmp/raylab-peers}
runs=${2:-5}
skip=${SKIP:-}
threads=2
scenes=(balls-4 gears-4 mount-6 rings-7 teapot-12 tetra-6 tree-11)

die() { echo "peers/run.sh: $*" >&2; exit 1; }
wants() { [[ ",$skip," != *",$1,"* ]]; }

for need in tools/embree_anchor.py tools/povray-time.sh scenes/spd scenes/spd-pov; do
    [[ -e "$shared/$need" ]] || die "missing $shared/$need (set SHARED to the shared folder)"
done
if wants embree; then
    python3 -c "import embreex, numpy" 2>/dev/null || die "needs python3 with embreex and numpy (pip install embreex numpy)"
fi
if wants povray; then
    command -v povray >/dev/null || die "needs POV-Ray 3.7 (apt-get install povray)"
fi
mkdir -p "$out"
echo "# raylab peers, $(date -u '+%Y-%m-%d %H:%M UTC'), $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs"
echo "output: $out"

if wants embree || wants crates; then
    [[ -e "$out/dump/manifest.json" ]] || python3 "$shared/tools/embree_anchor.py" --dump "$out/dump" >&2
fi
if wants embree; then
    python3 "$shared/tools/embree_anchor.py" --reps "$runs" --robust 0 --skip-probe --idle-timeout 5 \
        --json "$out/embree.json" >"$out/embree.md"
    cat "$out/embree.md"
fi
if wants crates; then
    # raylab's own build folder: the library is built there already.
    cargo build --release --quiet --manifest-path "$root/peers/Cargo.toml" --target-dir "$root/target"
    embree_json=()
    [[ -e "$out/embree.json" ]] && embree_json=(--embree "$out/embree.json")
    "$root/target/release/raylab-peers" "$out/dump" --reps "$runs" "${embree_json[@]}" | tee "$out/crates.md"
fi

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

if wants povray; then
    cargo build --release --quiet --manifest-path "$root/Cargo.toml" --bin raylab
    raylab=("$root/target/release/raylab" render --width 512 --height 512 --max-depth 5
            --block-size 1 --threads "$threads" --nff-lights povray)
    echo
    echo "### POV-Ray 3.7 vs raylab, 512x512, depth 5, no AA, $threads threads, median of $runs (seconds)"
    echo
    echo "| scene | POV whole | raylab whole | POV ÷ raylab | POV trace | raylab render | POV ÷ raylab |"
    echo "|---|---|---|---|---|---|---|"
    for scene in "${scenes[@]}"; do
        pov_scene="$shared/scenes/spd-pov/$scene.pov"
        nff="$shared/scenes/spd/$scene.nff"
        # One warm-up run each, then POV-Ray and raylab by turns, so that both meet the same
        # load on a shared machine; POV-Ray's own trace time is read from each of its runs.
        POV_WARMUP=0 "$shared/tools/povray-time.sh" "$pov_scene" "$threads" 1 >/dev/null
        "${raylab[@]}" "$nff" -o "$out/raylab-$scene.png" >/dev/null
        pov_walls=() pov_traces=() walls=() renders=()
        for ((i = 0; i < runs; i++)); do
            pov_log="$out/povray-$scene.log"
            POV_WARMUP=0 "$shared/tools/povray-time.sh" "$pov_scene" "$threads" 1 \
                "$out/povray-$scene.png" >"$pov_log"
            pov_walls+=("$(sed -n 's/^median wall: \([0-9.]*\) s.*/\1/p' "$pov_log")")
            pov_traces+=("$(sed -n 's/.*Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' "$pov_log")")
            t0=$(date +%s.%N)
            line=$("${raylab[@]}" "$nff" -o "$out/raylab-$scene.png")
            t1=$(date +%s.%N)
            walls+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')")
            renders+=("$(sed -n 's/^[0-9]*×[0-9]*: \([0-9.]*\) s.*/\1/p' <<<"$line")")
        done
        pov_whole=$(printf '%s\n' "${pov_walls[@]}" | median)
        pov_trace=$(printf '%s\n' "${pov_traces[@]}" | median)
        ray_whole=$(printf '%s\n' "${walls[@]}" | median)
        ray_render=$(printf '%s\n' "${renders[@]}" | median)
        awk -v s="$scene" -v pw="$pov_whole" -v rw="$ray_whole" -v pt="$pov_trace" -v rr="$ray_render" \
            'BEGIN { printf "| %s | %.3f | %.3f | %.1f× | %.3f | %.3f | %.1f× |\n", s, pw, rw, pw / rw, pt, rr, pt / rr }'
    done | tee "$out/povray.md"
fi

if wants bench; then
    cargo build --release --quiet --manifest-path "$root/Cargo.toml" --bin raylab
    echo
    "$root/target/release/raylab" bench --threads "$threads" --scaling --repeat "$runs" \
        --json "$out/bench.json" | tee "$out/bench.md"
fi
