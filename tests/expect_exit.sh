#!/usr/bin/env bash
# Runs a command and passes when it exits with the given status (README: exit codes); prints the
# command's output either way, so ctest can also match its message.
# Usage: expect_exit.sh STATUS COMMAND [ARGS...]
expected=$1
shift
"$@"
status=$?
if [ "$status" -ne "$expected" ]; then
  echo "expect_exit.sh: '$*' exited $status, expected $expected" >&2
  exit 1
fi
