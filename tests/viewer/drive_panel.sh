#!/usr/bin/env bash
# Drives a running glass-viewer with real X input events (xdotool), finding the panel's widgets
# by name in the viewer's --ui-map. STEPS is a file of one step a line:
#   click NAME          click the widget NAME (a tree node, checkbox, selectable, ...)
#   enter NAME=VALUE    Ctrl+click the slider NAME, type VALUE, Enter
#   key KEY             press KEY in the view (xdotool key names: c, Right, ...)
#   screenshot N        F12, and wait for the viewer's screenshot number N
# then Escape, which quits and saves the session and scene.
# usage: drive_panel.sh VIEWER OUTDIR STEPS [viewer arguments...]; the viewer's output goes to
# OUTDIR/viewer.log; exit status: the viewer's, or 1 when a step times out.
set -u
. "$(dirname "$0")/viewer_lib.sh"
viewer=$1 dir=$2 steps=$3
shift 3
map="$dir/ui-map.txt"
start_viewer "$viewer" "$dir" "$@" --ui-map "$map"
focus_window

# A point of widget $1 as the map has it, "x y": near its left end (a slider's rectangle ends
# with its label), half-way down (waiting up to 30 s for it to be drawn).
point() {
    local rect
    for _ in $(seq 300); do
        rect=$(awk -F '\t' -v name="$1" '$1 == name { print $2; exit }' "$map" 2>/dev/null)
        if [ -n "$rect" ]; then
            set -- $rect
            echo "$(($1 + 12)) $((($2 + $4) / 2))"
            return 0
        fi
        kill -0 "$pid" 2>/dev/null || fail "viewer exited waiting for '$1'"
        sleep 0.1
    done
    fail "no widget '$1' after 30 s"
}
# Clicks widget $1, the button held a while: Dear ImGui 1.86's GLFW backend can miss a press
# and release (of a button or a key) that fall in one frame.
click() {
    local xy
    xy=$(point "$1") || exit 1
    xdotool mousemove --window "$window" $xy mousedown 1
    sleep 0.5
    xdotool mouseup 1
    sleep 0.5
}
# Ctrl+click makes a slider a text field with its text selected: types $2 and Enter.
enter() {
    local xy
    xy=$(point "$1") || exit 1
    xdotool mousemove --window "$window" $xy keydown ctrl mousedown 1
    sleep 0.5
    xdotool mouseup 1 keyup ctrl
    sleep 0.5
    xdotool type --delay 60 "$2"
    xdotool keydown Return # held a while, as the button is
    sleep 0.3
    xdotool keyup Return
    sleep 0.5
}

while IFS= read -r step || [ -n "$step" ]; do
    case "$step" in
    "click "*) click "${step#click }" ;;
    "enter "*)
        assignment=${step#enter }
        enter "${assignment%=*}" "${assignment##*=}"
        ;;
    "key "*)
        xdotool key "${step#key }"
        sleep 0.3
        ;;
    "screenshot "*) screenshot "${step#screenshot }" ;;
    "") ;;
    *) fail "unknown step '$step'" ;;
    esac
done <"$steps"
sleep 0.3
quit_viewer
