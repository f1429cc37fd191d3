#!/bin/bash
# `plait ab` as a Slurm job array: each array task renders one shard of the
# run, into a folder of its own on a file system every node sees.
#
#   jobid=$(sbatch --parsable examples/cluster/slurm-ab.sh)
#   sbatch --dependency=afterok:"$jobid" \
#       --wrap "plait ab merge shards/$jobid/* --out report-$jobid"
#
# plait reads its shard from SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_MIN,
# SLURM_ARRAY_TASK_STEP and SLURM_ARRAY_TASK_COUNT, so the array may start
# at any id (--array=1-8) or step (--array=0-14:2); a list with gaps
# (--array=1,4,9) is refused. Every task must run the same plait on the same
# checkout with the same arguments: the shards carry a fingerprint of the
# plan (pipelines, shaders, scenes, flags, plait's version), and
# `plait ab merge` refuses shards of different plans.
#SBATCH --job-name=plait-ab
#SBATCH --array=0-4
#SBATCH --cpus-per-task=4
#SBATCH --gres=gpu:1
#SBATCH --time=00:30:00
#SBATCH --output=plait-ab-%A_%a.log
set -euo pipefail

plait ab pipelines/occupancy.toml pipelines/deep_opacity.toml pipelines/opacity_shadow_maps.toml \
    --reference pipelines/reference.toml \
    --sweep params.light_size=256,512,1024 \
    --scene examples/scenes/small.toml --size 960x720 --repeats 5 \
    --out "shards/$SLURM_ARRAY_JOB_ID/$SLURM_ARRAY_TASK_ID"
