#!/bin/bash
# Submits the tiles of SCENE as a job array of TILES tasks (64 unless set), and the merge into
# OUTPUT as a job that starts once all of them have succeeded. Run it on the login node, in a
# folder on the shared filesystem:
#
#   TILES=64 CPUS=1 examples/cluster/slurm/submit.sh SCENE OUTPUT [raylab render options…]
#
# Each tile's task asks for CPUS cores (1 unless set).
# The tiles go to OUTPUT's name with .parts (final.png → final.parts/). Prints the two job IDs.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: $0 SCENE OUTPUT [raylab render options…]" >&2
    exit 2
fi
here=$(dirname "$0")
scene=$1
output=$2
shift 2
parts="${output%.*}.parts"
tiles=${TILES:-64}
tiles_job=$(sbatch --parsable --array="0-$((tiles - 1))" --cpus-per-task="${CPUS:-1}" \
    "$here/tiles.sbatch" "$scene" "$parts" "$@")
tiles_job=${tiles_job%%;*} # --parsable prints "ID" or "ID;CLUSTER"
merge_job=$(sbatch --parsable --dependency="afterok:$tiles_job" "$here/merge.sbatch" "$parts" "$output")
echo "tiles: job $tiles_job ($tiles tasks); merge: job ${merge_job%%;*} → $output"
