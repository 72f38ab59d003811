#!/usr/bin/env bash
# The type check and the test suite of `make test`, side by side: mypy (one process, about 40 s
# of CPU from a cold cache, as on a clean clone) runs while pytest runs on two workers, so its
# time is shared with the suite's instead of added to it. Both must pass: the status is the
# first failure's (mypy's printed after the tests, whatever their outcome).
# Usage: scripts/types-and-tests.sh BIN  (BIN: the virtual environment's bin folder)
set -u
bin="$1"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
"$bin/mypy" >"$log" 2>&1 &
mypy_pid=$!
# worksteal: a worker that runs out of tests takes some of the other's queue, so the two end
# together (measured: 300 s against 323 s for xdist's default chunks, the same suite)
"$bin/python" -m pytest -n 2 --dist worksteal -q
tests=$?
wait "$mypy_pid"
types=$?
echo "$bin/mypy"
cat "$log"
if [ "$types" -ne 0 ]; then
  exit "$types"
fi
exit "$tests"
