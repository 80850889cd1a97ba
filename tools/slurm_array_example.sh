#!/usr/bin/env bash
# Example (not run by the tests): a tiled sacfuse job as a SLURM array, one array task per tile with views, plus a
# merge job that starts when every task has ended. All nodes must share CONFIG's output.dir (NFS, Lustre, ...);
# tiles are claimed atomically (DIR/tiles/<id>.claim), so resubmitting, or mixing with `sacfuse run` or GNU
# parallel workers, never computes a tile twice, and a done tile is skipped.
#
# Submit from a login node (sacfuse on PATH, CONFIG with tiling.tile_size_m > 0):
#   CONFIG=job.yaml
#   N=$(sacfuse plan "$CONFIG" --list | wc -l)            # writes DIR/plan.json once, shared by every task
#   JOB=$(sbatch --parsable --array=0-$((N - 1)) --export=ALL,CONFIG="$CONFIG" tools/slurm_array_example.sh)
#   sbatch --dependency=afterany:"$JOB" --wrap "sacfuse merge $CONFIG"   # exit 1 lists tiles still missing
# Failed or timed-out tiles: `sacfuse status CONFIG`, then resubmit the array (done tiles exit at once) or run
# `sacfuse run CONFIG`. A claim left by a killed task is taken over after tiling.claim_timeout_s (default 6 h)
# unless the task's pid is checked on the same host; lower it to at least the longest tile's wall time.
#
#SBATCH --job-name=sacfuse-tile
#SBATCH --array=0-64               # 0..N-1, N = number of lines of `sacfuse plan CONFIG --list` (overridden above)
#SBATCH --cpus-per-task=8
#SBATCH --mem=16G                  # see the memory column of `sacfuse plan CONFIG`
#SBATCH --time=02:00:00
#SBATCH --output=sacfuse-tile-%A_%a.log
set -euo pipefail

: "${CONFIG:?set CONFIG to the YAML config of the job (sbatch --export=ALL,CONFIG=job.yaml)}"
: "${SLURM_ARRAY_TASK_ID:?run this script as a SLURM array task}"

# The n-th tile id (0-based) of the shared plan.
TILE_ID=$(sacfuse plan "$CONFIG" --list | sed -n "$((SLURM_ARRAY_TASK_ID + 1))p")
if [ -z "$TILE_ID" ]; then
  echo "array task $SLURM_ARRAY_TASK_ID: no such tile (the plan has fewer tiles); nothing to do"
  exit 0
fi
echo "array task $SLURM_ARRAY_TASK_ID: tile $TILE_ID on $(hostname)"
exec sacfuse tile "$CONFIG" --id "$TILE_ID"
