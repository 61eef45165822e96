#!/usr/bin/env bash
# A branch in its own work tree with its own virtualenv, for one engineer (or helper) of a session:
#   tools/worktree.sh NAME [BASE]   -> /work/wt/NAME on branch NAME (from BASE, default main)
# The virtualenv is made by uv from the package index cache in seconds (an editable install of the
# work tree, with the extras `make test` uses); the tree's own `make` targets then find .venv ready.
set -euo pipefail
name=${1:?usage: tools/worktree.sh NAME [BASE]}
base=${2:-main}
top=$(git rev-parse --show-toplevel)
root=${WT_ROOT:-$(dirname "$top")/wt}
dir="$root/$name"
mkdir -p "$root"
if [ ! -d "$dir" ]; then
  if git show-ref --quiet "refs/heads/$name"; then git worktree add -q "$dir" "$name"
  else git worktree add -q -b "$name" "$dir" "$base"; fi
fi
cd "$dir"
if [ ! -x .venv/bin/tyrelab ]; then
  uv=$(command -v uv || true)
  [ -n "$uv" ] || { python3 -m pip install -q --user uv >/dev/null; uv=$(python3 -m site --user-base)/bin/uv; }
  "$uv" venv -q --seed --python "$(command -v python3)" .venv
  # --compile-bytecode: with PYTHONDONTWRITEBYTECODE=1 nothing writes .pyc later, and every subprocess
  # a test starts would compile scipy and pandas from source again (see the Makefile's `compile`)
  "$uv" pip install -q --python .venv/bin/python --compile-bytecode -e ".[${EXTRAS:-dev,dask,formats,browser}]"
  touch .venv/bin/tyrelab
fi
echo "$dir"
