#!/usr/bin/env bash
# check-glsl.sh DIR: every program dumped to DIR (GLASS_DUMP_SHADERS, glass-capture
# --dump-shaders: <program>-<hash>.<vert|frag|comp>) compiled and linked by the Khronos reference
# compiler, glslangValidator, against the GLSL 4.50 core specification its #version names.
# Fails on any error or warning, naming the program and quoting the compiler; fails too when DIR
# holds no program (nothing was dumped, so nothing was checked).
set -euo pipefail
dir=${1:?usage: check-glsl.sh DIR}
command -v glslangValidator >/dev/null ||
    { echo "check-glsl.sh: no glslangValidator (scripts/deps installs glslang-tools)" >&2; exit 1; }
[ -d "$dir" ] || { echo "check-glsl.sh: $dir does not exist: no program was dumped" >&2; exit 1; }

# one line per program: its stages' files, linked together
mapfile -t programs < <(cd "$dir" && ls | sed -n 's/\.\(vert\|frag\|comp\)$//p' | sort -u)
[ ${#programs[@]} -gt 0 ] || { echo "check-glsl.sh: $dir holds no program" >&2; exit 1; }

check() {
    local program=$1 stages=() log
    for stage in vert frag comp; do
        [ -f "$program.$stage" ] && stages+=("$program.$stage")
    done
    if ! log=$(glslangValidator -l "${stages[@]}" 2>&1) || grep -q "WARNING" <<<"$log"; then
        printf '== %s\n%s\n' "$program" "$log"
        return 1
    fi
}
export -f check
cd "$dir"
failed=0
printf '%s\n' "${programs[@]}" | xargs -P "$(nproc)" -I{} bash -c 'check "$1"' _ {} || failed=1
stages=$(ls | grep -c '\.\(vert\|frag\|comp\)$')
if [ $failed -ne 0 ]; then
    echo "check-glsl.sh: glslangValidator refuses the programs above (of ${#programs[@]} in $dir)"
    exit 1
fi
echo "check-glsl.sh: glslangValidator accepts all ${#programs[@]} programs ($stages stages) in $dir"
