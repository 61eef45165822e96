#!/usr/bin/env bash
# Queue this work tree's branch (at its current commit) for the merge queue.
#   tools/submit.sh            (from inside your work tree, after committing)
# The queue daemon merges everything queued onto main as one batch and gates it (tools/merge_queue.sh);
# the outcome is appended to ../wt/QUEUE-RESULTS (grep your branch name: LANDED, REJECTED, or
# "does not merge cleanly" -> `git merge main`, resolve, commit, submit again).
set -euo pipefail
[ -z "$(git status --porcelain --untracked-files=no)" ] || { echo "submit: commit your changes first" >&2; exit 2; }
branch=$(git rev-parse --abbrev-ref HEAD); sha=$(git rev-parse HEAD)
[ "$branch" != main ] || { echo "submit: work on a branch, not main" >&2; exit 2; }
main_dir=$(git worktree list --porcelain | awk 'NR==1{print $2}')
root=${WT_ROOT:-$(dirname "$main_dir")/wt}
echo "$branch@$sha" >> "$root/QUEUE"
echo "submit: queued $branch@${sha:0:8}; watch $root/QUEUE-RESULTS"
