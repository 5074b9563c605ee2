#!/bin/sh
# Runs a command on a virtual X server (xvfb-run -a, from display DISPLAY up). When the command
# could not connect to the server it was given at all ("bad X server connection": seen in CI
# once in ~10 full runs, 1 s into ParaView.pvpython.FigureLayout, never reproduced alone), it is
# run once more on another display; a test that connected and failed is not run again.
# Usage: run_with_xvfb.sh <xvfb-run> <display> <screen WxHxD> <command...>
set -u
xvfb_run=$1 display=$2 screen=$3
shift 3
log=$(mktemp)
for attempt in 1 2; do
  "$xvfb_run" -a -n "$display" -s "-screen 0 $screen" "$@" > "$log" 2>&1
  status=$?
  cat "$log"
  if [ "$status" -eq 0 ] || ! grep -q "bad X server connection" "$log"; then
    break
  fi
  echo "run_with_xvfb.sh: no connection to the X server on attempt $attempt; once more"
  display=$((display + 5))
done
rm -f "$log"
exit "$status"
