#!/bin/bash
# A turntable on a Slurm cluster: each task of a job array renders one shard of the frames into a
# shared folder, and a last job joins them. Not run on a cluster here: written from Slurm's
# documentation of job arrays (SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT) and dependencies.
#
# Submit:  jobid=$(sbatch --parsable slurm-turntable.sh)
#          sbatch --dependency=afterok:$jobid --wrap 'rastray join frames/*.png -o spin.gif'
#SBATCH --job-name=rastray-turntable
#SBATCH --array=1-8
#SBATCH --cpus-per-task=8
#SBATCH --time=00:30:00
#SBATCH --output=rastray-%A_%a.log
set -euo pipefail
mkdir -p frames
rastray render scene.toml -s 1920x1080 --samples 2 --turntable 240 \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --shard "${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}" \
  -o 'frames/{frame:04}.png'
