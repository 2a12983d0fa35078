#!/usr/bin/env bash
# Installs this build (cmake --install into a temporary prefix, or the Debian package made by
# cpack and unpacked into a temporary root), then configures, builds and tests
# examples/downstream against that tree alone.
#   downstream.sh install BUILD_DIR SOURCE_DIR [CMAKE_ARG...]
#   downstream.sh deb     BUILD_DIR SOURCE_DIR [CMAKE_ARG...]
# The CMake arguments configure the example (this build's compiler and flags).
set -euo pipefail
mode=$1 build=$2 source=$3
shift 3
work=$(mktemp -d "${TMPDIR:-/tmp}/glass-downstream.XXXXXX")
trap 'rm -rf "$work"' EXIT

case "$mode" in
install)
    prefix="$work/prefix"
    cmake --install "$build" --prefix "$prefix" >/dev/null
    ;;
deb)
    (cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/package" >/dev/null)
    deb=$(ls "$work"/package/glass_*.deb)
    echo "package: $(basename "$deb")"
    depends=$(dpkg-deb -f "$deb" Depends)
    echo "Depends: $depends"
    # what the programs and libglass-engine link, and GLM for the headers
    for needed in libglm-dev libepoxy0 libglfw3 libdraco libmeshoptimizer libwebp libjpeg62-turbo \
        libosdgpu libembree3 libc6 libstdc++6; do
        grep -q "$needed" <<<"$depends" || { echo "FAIL: Depends lacks $needed"; exit 1; }
    done
    dpkg-deb -x "$deb" "$work/root"
    prefix="$work/root/usr"
    for file in bin/glass-capture bin/glass-viewer lib/cmake/Glass/GlassConfig.cmake \
                include/glass/engine/plugin/Plugin.h share/glass/assets/models/glass_figure.glb; do
        [ -e "$prefix/$file" ] || { echo "FAIL: the package lacks /usr/$file"; exit 1; }
    done
    ;;
*)
    echo "usage: downstream.sh install|deb BUILD_DIR SOURCE_DIR" >&2
    exit 2
    ;;
esac

# The loadable module must not pull a UI library or the ray tracer into a host that renders.
module=$(ls "$prefix"/lib/glass/libglass_refraction.so)
if readelf -d "$module" | grep -E "NEEDED.*(imgui|embree|glfw)"; then
    echo "FAIL: $module needs a library only the viewer or the reference should"
    exit 1
fi
"$prefix/bin/glass-capture" --help >/dev/null

cmake -S "$source/examples/downstream" -B "$work/example" -G Ninja \
      -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
      -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF "$@" >"$work/configure.log" ||
    { cat "$work/configure.log"; exit 1; }
found=$(grep -o "Glass [0-9.]* from .*" "$work/configure.log")
echo "$found"
[[ "$found" == *" from $prefix/"* ]] || { echo "FAIL: Glass was not found in $prefix"; exit 1; }
cmake --build "$work/example" >"$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
ctest --test-dir "$work/example" --output-on-failure
