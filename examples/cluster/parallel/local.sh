#!/bin/bash
# TILES tiles of SCENE rendered by GNU parallel on this machine, one job per core at a time,
# then merged into OUTPUT:
#
#   examples/cluster/parallel/local.sh SCENE TILES OUTPUT [raylab render options…]
#
# parallel numbers its jobs from 1 in PARALLEL_SEQ, which `--tile auto` reads (job 1 renders
# tile 0); the tiles go to OUTPUT's name with .parts (final.png → final.parts/tile-1.exr, …).
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: $0 SCENE TILES OUTPUT [raylab render options…]" >&2
    exit 2
fi
scene=$1
tiles=$2
output=$3
shift 3
parts="${output%.*}.parts"
mkdir -p "$parts"
parallel -q --halt now,fail=1 \
    raylab render "$scene" --tile auto --of "$tiles" --threads 1 -o "$parts/tile-{#}.exr" "$@" \
    ::: $(seq "$tiles")
raylab merge "$parts" -o "$output"
