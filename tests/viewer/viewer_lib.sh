# Shared by the scripts that drive a running glass-viewer with real X input events (xdotool)
# inside an X server that xvfb-run provides. Source it, then: start_viewer VIEWER OUT [args...];
# focus_window; screenshot N; quit_viewer (exits with the viewer's status).

# Starts the viewer in the background, its output in $out/viewer.log; sets $pid, $out.
start_viewer() {
    local viewer=$1
    out=$2
    shift 2
    "$viewer" "$@" --screenshot-dir "$out" >"$out/viewer.log" 2>&1 &
    pid=$!
}

fail() {
    echo "$(basename "$0"): $*" >&2
    kill "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    cat "$out/viewer.log" >&2
    exit 1
}

# The window exists before it is mapped; focusing an unmapped window is an X error (BadMatch),
# so wait until it is viewable (slow starts: sanitizer builds). Sets $window.
focus_window() {
    window=$(timeout 60 xdotool search --sync --onlyvisible --name '^glass-viewer$' | head -n 1)
    [ -n "$window" ] || fail "no visible glass-viewer window after 60 s"
    # No window manager: put the pointer over the window and give it the keyboard focus.
    local focused=0
    for _ in $(seq 50); do
        xdotool mousemove --window "$window" 40 40 2>/dev/null &&
            xdotool windowfocus --sync "$window" 2>/dev/null && focused=1 && break
        sleep 0.1
    done
    [ "$focused" = 1 ] || fail "cannot focus the viewer window"
}

# Presses F12 and waits (up to 60 s) for the viewer to write screenshot number $1.
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

# Escape (which saves the session and scene), then the viewer's exit status and log.
quit_viewer() {
    xdotool key Escape
    for _ in $(seq 300); do
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    kill -0 "$pid" 2>/dev/null && fail "viewer still running 30 s after Escape"
    wait "$pid"
    local status=$?
    cat "$out/viewer.log"
    exit "$status"
}
