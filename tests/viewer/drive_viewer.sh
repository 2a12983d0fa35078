#!/usr/bin/env bash
# Drives a running glass-viewer with real X input events (xdotool), inside an X server that
# xvfb-run provides. Writes screenshots through the viewer's own F12 key:
#   1: as started; 2: again with no input (must equal 1); 3: after the key M (next method);
#   4: after a mouse drag across the view (orbit).
# usage: drive_viewer.sh VIEWER OUTDIR [viewer arguments...]; the viewer's output goes to
# OUTDIR/viewer.log; exit status: the viewer's, or 1 when a step times out.
set -u
viewer=$1 out=$2
shift 2
"$viewer" "$@" --screenshot-dir "$out" >"$out/viewer.log" 2>&1 &
pid=$!

fail() {
    echo "drive_viewer: $*" >&2
    kill "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    cat "$out/viewer.log" >&2
    exit 1
}
# Waits (up to 60 s) for the viewer to write screenshot number $1.
screenshot() {
    local file
    file=$(printf '%s/glass-viewer-%04d.png' "$out" "$1")
    xdotool key F12
    for _ in $(seq 600); do
        [ -s "$file" ] && return 0
        kill -0 "$pid" 2>/dev/null || fail "viewer exited before screenshot $1"
        sleep 0.1
    done
    fail "no screenshot $1 after 60 s"
}

# The window exists before it is mapped; focusing an unmapped window is an X error (BadMatch),
# so wait until it is viewable (slow starts: sanitizer builds).
window=$(timeout 60 xdotool search --sync --onlyvisible --name '^glass-viewer$' | head -n 1)
[ -n "$window" ] || fail "no visible glass-viewer window after 60 s"
# No window manager: put the pointer over the window and give it the keyboard focus.
focused=0
for _ in $(seq 50); do
    xdotool mousemove --window "$window" 40 40 2>/dev/null &&
        xdotool windowfocus --sync "$window" 2>/dev/null && focused=1 && break
    sleep 0.1
done
[ "$focused" = 1 ] || fail "cannot focus the viewer window"

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
xdotool key Escape
for _ in $(seq 300); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
done
kill -0 "$pid" 2>/dev/null && fail "viewer still running 30 s after Escape"
wait "$pid"
status=$?
cat "$out/viewer.log"
exit "$status"
