#!/usr/bin/env bash
# Drives a running glass-viewer with real X input events (xdotool), inside an X server that
# xvfb-run provides. Writes screenshots through the viewer's own F12 key:
#   1: as started; 2: again with no input (must equal 1); 3: after the key M (next method);
#   4: after a mouse drag across the view (orbit).
# usage: drive_viewer.sh VIEWER OUTDIR [viewer arguments...]; the viewer's output goes to
# OUTDIR/viewer.log; exit status: the viewer's, or 1 when a step times out.
set -u
. "$(dirname "$0")/viewer_lib.sh"
start_viewer "$@"
focus_window

screenshot 1
screenshot 2
xdotool key m
screenshot 3
xdotool mousemove --window "$window" 60 150 mousedown 1
for x in 90 120 150 180 210; do
    sleep 0.1
    xdotool mousemove --window "$window" "$x" 150
done
xdotool mouseup 1
sleep 0.3
screenshot 4
quit_viewer
