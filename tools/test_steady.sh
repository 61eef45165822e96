#!/usr/bin/env bash
# The default suite again and again, to find the next flaky test (issue 48; `make test-steady`):
#   tools/test_steady.sh [ROUNDS] [LOAD]
# Each round runs `pytest -m "not slow"` under -n auto and under -n 1; with LOAD > 0, LOAD busy
# processes (one core each) run beside it the whole time, as other work on the machine would.
# Stops at the first failure (exit 1) and names the round; a failure found is fixed at its cause
# (docs/testing.md: "Tests that never race the machine"), never retried.
set -euo pipefail
rounds=${1:-2}
load=${2:-0}
py=${PYTHON_BIN:-.venv/bin/python}
burners=()
stop() { for pid in "${burners[@]}"; do kill "$pid" 2>/dev/null || true; done; }
trap stop EXIT
for _ in $(seq 1 "$load"); do
  "$py" -c "while True: pass" &
  burners+=($!)
done
for round in $(seq 1 "$rounds"); do
  for n in auto 1; do
    echo "test-steady: round $round of $rounds, -n $n, $load busy process(es) beside"
    if ! "$py" -m pytest -q -m "not slow" -n "$n"; then
      echo "test-steady: FAILED in round $round (-n $n, load $load)" >&2
      exit 1
    fi
  done
done
echo "test-steady: $rounds round(s) under -n auto and -n 1 (load $load): no failure"
