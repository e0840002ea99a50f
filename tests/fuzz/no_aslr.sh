#!/bin/sh
# Runs "$@" with address randomisation off when the system lets a process turn it off (some
# containers refuse the personality call), else as it is: a fixed-seed fuzz run then replays
# the same inputs from run to run.
if setarch -R true 2>/dev/null; then
  exec setarch -R "$@"
fi
exec "$@"
