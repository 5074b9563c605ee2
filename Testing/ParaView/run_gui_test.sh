#!/bin/sh
# Runs a paraview.simple script inside the real ParaView GUI on a virtual X server.
# The GUI's exit code does not reflect the script's, so success is the PASSED file it writes.
# Usage: run_gui_test.sh <xvfb-run> <first display number> <paraview> <script> <plugin> <work dir>
set -u
xvfb_run=$1 display=$2 paraview=$3 script=$4
OTPARAM_PLUGIN=$5 OTPARAM_TEST_DIR=$6 OTPARAM_SCREENSHOT=1
export OTPARAM_PLUGIN OTPARAM_TEST_DIR OTPARAM_SCREENSHOT
rm -f "$OTPARAM_TEST_DIR/PASSED"
"$xvfb_run" -a -n "$display" -s "-screen 0 1280x1024x24" "$paraview" --dr "--script=$script" --exit
if ! test -f "$OTPARAM_TEST_DIR/PASSED"; then
  echo "the GUI script did not pass"
  cat "$OTPARAM_TEST_DIR/FAILURES" 2>/dev/null || echo "(no failed check: the script stopped early)"
  exit 1
fi
echo "GUI script passed; screenshot: $OTPARAM_TEST_DIR/power_diagram.png"
