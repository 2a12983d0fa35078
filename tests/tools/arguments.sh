#!/usr/bin/env bash
# Every tool's command line answers alike (samples/common/Cli.h): --help prints the generated
# help (its usage line and options) and exits 0; an unknown option exits 2 with a message that
# names it; a bad value exits 2 naming its option. usage: arguments.sh BIN_DIR
set -uo pipefail
bin="$1"
status=0
fail() {
    echo "FAIL: $*"
    status=1
}
# tool, then an option of its own with a value it refuses
checks=("glass-capture --size 0x5"
        "glass-bench --frames 0"
        "glass-compare --columns 0"
        "glass-cpu-bench --runs 0"
        "glass-generate-assets --out"
        "glass-inspect --vertices tpu"
        "glass-soak --frames 0"
        "glass-viewer --size 1x1")
for check in "${checks[@]}"; do
    read -r tool option value <<<"$check"
    help=$("$bin/$tool" --help 2>&1)
    rc=$?
    [ "$rc" = 0 ] || fail "$tool --help exits $rc"
    grep -q "^Usage: $tool" <<<"$help" || fail "$tool --help prints no usage line"
    grep -q -- "$option" <<<"$help" || fail "$tool --help does not list $option"
    err=$("$bin/$tool" --bogus 2>&1 >/dev/null)
    rc=$?
    [ "$rc" = 2 ] || fail "$tool --bogus exits $rc"
    grep -q "^$tool: unknown option --bogus" <<<"$err" || fail "$tool --bogus says: $err"
    # shellcheck disable=SC2086
    err=$("$bin/$tool" $option $value 2>&1 >/dev/null)
    rc=$?
    [ "$rc" = 2 ] || fail "$tool $option $value exits $rc"
    grep -q -- "^$tool: $option" <<<"$err" || fail "$tool $option $value says: $err"
done
[ "$status" = 0 ] && echo "every tool's arguments answer alike"
exit "$status"
