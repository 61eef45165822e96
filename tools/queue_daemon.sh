#!/usr/bin/env bash
# The merge queue's daemon: every 30 s, take everything in ../wt/QUEUE (one entry per submitted
# branch; a branch queued twice lands at its newest commit) and run tools/merge_queue.sh on it as one
# batch; outcomes go to ../wt/QUEUE-RESULTS. Stop it with kill; a batch under way finishes first.
set -uo pipefail
main_dir=$(git rev-parse --show-toplevel)
root=${WT_ROOT:-$(dirname "$main_dir")/wt}
touch "$root/QUEUE" "$root/QUEUE-RESULTS"
while true; do
  if [ -s "$root/QUEUE" ]; then
    mv "$root/QUEUE" "$root/QUEUE.taking"; touch "$root/QUEUE"
    # The newest entry per branch, in order of first submission.
    mapfile -t batch < <(tac "$root/QUEUE.taking" | awk -F@ '!seen[$1]++' | tac)
    rm -f "$root/QUEUE.taking"
    { echo "== $(date +%H:%M:%S) batch: ${batch[*]}"; (cd "$main_dir" && tools/merge_queue.sh "${batch[@]}"); echo "== $(date +%H:%M:%S) done"; } >> "$root/QUEUE-RESULTS" 2>&1
  fi
  sleep 30
done
