#!/usr/bin/env bash
# usage: scripts/timed.sh STAGE COMMAND [ARGS...]
# Runs COMMAND, then prints one line with how long the stage took ("make test: STAGE: N s"),
# so that a CI log shows where `make test`'s time goes. Exits with COMMAND's status.
set -uo pipefail
stage=$1
shift
start=$(date +%s)
"$@"
status=$?
echo "make test: $stage: $(($(date +%s) - start)) s$([[ $status == 0 ]] || echo " (failed, exit $status)")"
exit $status
