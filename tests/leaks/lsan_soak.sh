#!/usr/bin/env bash
# A short soak under LeakSanitizer (the asan preset's build). Fails on any direct leak, and on
# indirect leaks beyond the two 56-byte blocks that Mesa's llvmpipe leaves per process: they are
# allocated from its JIT-compiled code (anonymous executable memory, so no frame can be named or
# suppressed), point only at each other, and appear in every process that draws, project code
# or not. usage: lsan_soak.sh GLASS_SOAK
set -u
soak=$1
log=$(mktemp)
trap 'rm -f "$log"' EXIT
ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 LSAN_OPTIONS=exitcode=0 \
    "$soak" --frames 300 --switch-every 12 --resize-every 24 --report-every 6 >"$log" 2>&1
status=$?
cat "$log"
[ "$status" = 0 ] || { echo "lsan_soak: the soak failed ($status)"; exit 1; }
if grep -q "Direct leak" "$log"; then
    echo "lsan_soak: direct leaks"
    exit 1
fi
indirect=$(grep -Eo "Indirect leak of [0-9]+ byte" "$log" | awk "{ sum += \$4 } END { print sum + 0 }")
indirect=${indirect:-0}
if [ "$indirect" -gt 112 ]; then
    echo "lsan_soak: $indirect bytes of indirect leaks, more than llvmpipe's known 112"
    exit 1
fi
echo "lsan_soak: no direct leaks; indirect: $indirect bytes (llvmpipe's known blocks: up to 112)"
