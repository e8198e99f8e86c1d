#!/usr/bin/env bash
# Submits a softtrace job to Slurm (README "Clusters"):
#   submit.sh tiles N SCENE OUT.exr [render options]
#       N array tasks render tile I/N to OUT.tile-I-of-N.exr; a job that runs only when all
#       succeeded merges them into OUT.exr.
#   submit.sh frames F SCENE OUT.####.exr [render options]
#       F array tasks render frames 0..F-1 of the scene's animation.
# Logs: OUT.logs/ (one per task). Prints the job ids on stdout ("RENDER MERGE" or "RENDER").
# Slurm's own variables choose the rest, e.g. SBATCH_PARTITION, SBATCH_TIMELIMIT, and
# SOFTTRACE=/shared/path/softtrace the binary (default: softtrace on PATH).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

usage() {
  echo "usage: submit.sh tiles N SCENE OUT.exr [render options]" >&2
  echo "       submit.sh frames F SCENE OUT.####.exr [render options]" >&2
  exit 2
}
[ $# -ge 4 ] || usage
mode=$1 count=$2 scene=$3 out=$4
shift 4
[[ $count =~ ^[1-9][0-9]*$ ]] || usage
base=${out%.exr}
name=${base%%#*}
logs="${name%.}.logs"
mkdir -p "$logs"

case "$mode" in
  tiles)
    render=$(sbatch --parsable --array=0-$((count - 1)) --output="$logs/%x-%A_%a.log" \
      "$here/render.sbatch" tiles "$count" "$scene" "$base" "$@")
    merge=$(sbatch --parsable --dependency=afterok:"$render" --kill-on-invalid-dep=yes \
      --output="$logs/%x-%j.log" "$here/merge.sbatch" "$count" "$base" "$out")
    echo "submitted: $count tiles as job $render, the merge into $out as job $merge; logs in $logs/" >&2
    echo "$render $merge"
    ;;
  frames)
    render=$(sbatch --parsable --array=0-$((count - 1)) --output="$logs/%x-%A_%a.log" \
      "$here/render.sbatch" frames "$scene" "$out" "$@")
    echo "submitted: $count frames as job $render; logs in $logs/" >&2
    echo "$render"
    ;;
  *) usage ;;
esac
