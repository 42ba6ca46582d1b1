#!/bin/bash
# TILES tiles of SCENE rendered by GNU parallel on the machines of NODES over ssh, then merged
# here into OUTPUT:
#
#   examples/cluster/parallel/ssh.sh NODES SCENE TILES OUTPUT [raylab render options…]
#
# NODES lists one ssh login a line (node1, user@node2; this machine too, by its name, not `:`).
# No shared filesystem: the scene is copied into ~/raylab-work on each machine before its
# first job (--basefile), each tile is copied back into OUTPUT's name with .parts (final.png →
# final.parts/) when its job ends (--return), and the folder is deleted afterwards
# (--cleanup). Each machine needs raylab on the PATH of a non-interactive ssh command, and
# rsync; each runs one job at a time, which uses all of its cores. A scene that reads other
# files (textures, meshes) needs them sent too: one --basefile each.
set -euo pipefail
if [ $# -lt 4 ]; then
    echo "usage: $0 NODES SCENE TILES OUTPUT [raylab render options…]" >&2
    exit 2
fi
nodes=$1
scene=$2
tiles=$3
output=$4
shift 4
parts="${output%.*}.parts"
mkdir -p "$parts"
# The scene file goes to each machine (a built-in spd: scene needs nothing); a /./ in a
# transferred name: what follows it is the name on the other machine.
send=()
if [ -f "$scene" ]; then
    send=(--basefile "$(cd "$(dirname "$scene")" && pwd)/./$(basename "$scene")")
    scene=$(basename "$scene")
fi
parallel -q --halt now,fail=1 --sshloginfile "$nodes" --jobs 1 --workdir raylab-work \
    "${send[@]}" --return "$(cd "$parts" && pwd)/./tile-{#}.exr" --cleanup \
    raylab render "$scene" --tile auto --of "$tiles" -o "tile-{#}.exr" "$@" \
    ::: $(seq "$tiles")
raylab merge "$parts" -o "$output"
