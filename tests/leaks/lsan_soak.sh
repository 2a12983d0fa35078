#!/usr/bin/env bash
# A short soak under LeakSanitizer (the asan preset's build). Fails on any direct leak that named
# code allocated, and on indirect leaks beyond the two 56-byte blocks that Mesa's llvmpipe leaves
# per process: they are allocated from its JIT-compiled code (anonymous executable memory, so no
# frame can be named or suppressed), point only at each other, and appear in every process that
# draws, project code or not. usage: lsan_soak.sh GLASS_SOAK
set -u
soak=$1
log=$(mktemp)
trap 'rm -f "$log"' EXIT
ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 LSAN_OPTIONS=exitcode=0 \
    "$soak" --frames 300 --switch-every 12 --resize-every 21 --report-every 6 >"$log" 2>&1
status=$?
cat "$log"
[ "$status" = 0 ] || { echo "lsan_soak: the soak failed ($status)"; exit 1; }
# A direct leak counts when a frame above the allocator is the project's code (its libraries,
# the soak, its sources: every such frame is named, with frame pointers and symbols). Debian's
# Mesa leaves one 128-byte block in every process that makes a context, before this project's
# code draws anything (seen with glass-inspect --vertices gpu too), allocated from a driver
# unloaded at exit: its return address is reported in no module, or in whatever library the
# symboliser finds below it once the driver is gone (libubsan, in the asan preset's runs).
read -r named unnamed < <(awk '
    /^Direct leak of/ { if (open) close_block(); open = 1; bytes = $4; own = 0; next }
    /^(Indirect leak|SUMMARY)/ { if (open) close_block(); open = 0; next }
    open && /^ +#[1-9][0-9]* / && /libglass|glass-soak|\/(engine|plugin_refraction|samples)\// { own = 1 }
    function close_block() { if (own) named += bytes; else unnamed += bytes }
    END { if (open) close_block(); print named + 0, unnamed + 0 }' "$log")
if [ "$named" -gt 0 ]; then
    echo "lsan_soak: $named bytes of direct leaks from the project's code"
    exit 1
fi
indirect=$(grep -Eo "Indirect leak of [0-9]+ byte" "$log" | awk "{ sum += \$4 } END { print sum + 0 }")
indirect=${indirect:-0}
if [ "$indirect" -gt 112 ]; then
    echo "lsan_soak: $indirect bytes of indirect leaks, more than llvmpipe's known 112"
    exit 1
fi
echo "lsan_soak: no direct leaks from the project's code (elsewhere: $unnamed bytes); indirect:" \
    "$indirect bytes (llvmpipe's known blocks: up to 112)"
