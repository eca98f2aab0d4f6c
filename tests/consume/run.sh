#!/usr/bin/env bash
# Install-and-consume checks (meson suite 'install'), one mode per meson test:
#   run.sh pkgconfig  SRC BUILD VERSION  installs BUILD into a temporary DESTDIR, compiles
#       tests/consume/consumer.c with `$CC $(pkg-config --cflags --libs vtdyn)` against it and
#       runs it (LD_LIBRARY_PATH to the installed libdir, checked with ldd), then links it
#       statically (pkg-config --static, libvtdyn.a) and runs it again; the installed command
#       vtdyn (when built) runs without LD_LIBRARY_PATH and loads the installed library (its
#       rpath $ORIGIN/../libdir)
#   run.sh subproject SRC BUILD VERSION  a meson project (tests/consume/subproject) with SRC
#       linked as subprojects/vtdyn: dependency('vtdyn') through meson.override_dependency
#   run.sh nosundials SRC BUILD VERSION  configures SRC with -Dsundials=disabled, builds the
#       library and the tests of the instant and kinematic analyses, and runs them
# The consumer checks the double link's locking torque and joint-1 reaction against (29) and
# its version against VERSION. Exits 77 (meson's skip) when a tool is missing. Everything is
# written to a temporary directory that is removed at the end.
set -euo pipefail
mode=$1 src=$2 build=$3 version=$4
CC=${CC:-cc}
read -r -a cc_cmd <<< "$CC"

skip() { echo "SKIP: $*"; exit 77; }
need() { for t in "$@"; do command -v "$t" >/dev/null 2>&1 || skip "'$t' not found"; done; }
need "${cc_cmd[0]}" meson ninja
tmp=$(mktemp -d "${TMPDIR:-/tmp}/vtdyn-$mode.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
consumer=$src/tests/consume/consumer.c
jobs=2 # the project's machines have two cores

case $mode in
pkgconfig)
    need pkg-config readelf ldd
    meson install -C "$build" --no-rebuild --quiet --destdir "$tmp/dest" >/dev/null
    pc=$(find "$tmp/dest" -name vtdyn.pc -print -quit)
    [ -n "$pc" ] || { echo "no vtdyn.pc installed under $tmp/dest"; exit 1; }
    [ -f "$(find "$tmp/dest" -path '*/include/vtdyn/version.h' -print -quit)" ] ||
        { echo "vtdyn/version.h not installed"; exit 1; }
    export PKG_CONFIG_PATH=${pc%/*}
    # the .pc names the configured prefix; the files are under DESTDIR
    prefix=$(pkg-config --variable=prefix vtdyn)
    pc_args=(--define-variable=prefix="$tmp/dest$prefix")
    libdir=$(pkg-config "${pc_args[@]}" --variable=libdir vtdyn)
    [ "$(pkg-config --modversion vtdyn)" = "$version" ] ||
        { echo "vtdyn.pc says version $(pkg-config --modversion vtdyn), expected $version"; exit 1; }
    flags=(-std=c99 -Wall -Wextra -pedantic -Werror)

    read -r -a cflags <<< "$(pkg-config "${pc_args[@]}" --cflags vtdyn)"
    read -r -a libs <<< "$(pkg-config "${pc_args[@]}" --libs vtdyn)"
    echo "shared: $CC ${cflags[*]} consumer.c ${libs[*]} -lm"
    "${cc_cmd[@]}" "${flags[@]}" "${cflags[@]}" "$consumer" -o "$tmp/consumer_shared" "${libs[@]}" -lm
    # outputs are captured before grep -q reads them: with pipefail, grep -q quitting early
    # would fail the pipeline by SIGPIPE now and then
    deps=$(LD_LIBRARY_PATH=$libdir ldd "$tmp/consumer_shared")
    grep -qF "$libdir/libvtdyn.so" <<< "$deps" ||
        { echo "the consumer does not load the installed libvtdyn.so:"; LD_LIBRARY_PATH=$libdir ldd "$tmp/consumer_shared"; exit 1; }
    LD_LIBRARY_PATH=$libdir "$tmp/consumer_shared" "$version"

    read -r -a slibs <<< "$(pkg-config "${pc_args[@]}" --static --libs vtdyn)"
    # the static archive in place of -lvtdyn: the linker would otherwise take the .so
    for i in "${!slibs[@]}"; do
        if [ "${slibs[$i]}" = "-lvtdyn" ]; then slibs[$i]=$libdir/libvtdyn.a; fi
    done
    echo "static: $CC ${cflags[*]} consumer.c ${slibs[*]} -lm"
    "${cc_cmd[@]}" "${flags[@]}" "${cflags[@]}" "$consumer" -o "$tmp/consumer_static" "${slibs[@]}" -lm
    if grep -q 'NEEDED.*libvtdyn' <<< "$(readelf -d "$tmp/consumer_static")"; then
        echo "the static consumer still needs libvtdyn.so"; exit 1
    fi
    "$tmp/consumer_static" "$version"

    # the installed command finds the installed library by its rpath, relative to itself
    cmd=$(find "$tmp/dest" -path '*/bin/vtdyn' -print -quit)
    if [ -n "$cmd" ]; then
        deps=$(env -u LD_LIBRARY_PATH ldd "$cmd")
        loaded=$(sed -n 's/.*libvtdyn\.so[^ ]* => \([^ ]*\) .*/\1/p' <<< "$deps")
        [ -n "$loaded" ] && [ "$(dirname "$(realpath "$loaded")")" = "$(realpath "$libdir")" ] ||
            { echo "the installed vtdyn does not load the installed libvtdyn.so by itself:"; echo "$deps"; exit 1; }
        got=$(env -u LD_LIBRARY_PATH "$cmd" --version)
        [ "$got" = "vtdyn $version" ] || { echo "the installed vtdyn says '$got', expected 'vtdyn $version'"; exit 1; }
        echo "installed vtdyn: $got, libvtdyn.so through its rpath $(readelf -d "$cmd" | sed -n 's/.*R[UN]*PATH.*\[\(.*\)\]/\1/p')"
    else
        echo "no vtdyn installed (a build without URDF loading)"
    fi
    ;;
subproject)
    mkdir -p "$tmp/parent/subprojects"
    cp "$src/tests/consume/subproject/meson.build" "$consumer" "$tmp/parent/"
    ln -s "$(cd "$src" && pwd)" "$tmp/parent/subprojects/vtdyn"
    meson setup "$tmp/parent-build" "$tmp/parent" --force-fallback-for=vtdyn >"$tmp/setup.log" ||
        { cat "$tmp/setup.log"; exit 1; }
    grep -q "Subproject vtdyn finished" "$tmp/setup.log" || { cat "$tmp/setup.log"; echo "vtdyn was not used as a subproject"; exit 1; }
    meson compile -C "$tmp/parent-build" -j "$jobs" >"$tmp/build.log" || { cat "$tmp/build.log"; exit 1; }
    meson test -C "$tmp/parent-build" --no-rebuild --print-errorlogs --verbose consumer
    ;;
nosundials)
    need readelf nm
    meson setup "$tmp/nosun" "$src" -Dsundials=disabled >"$tmp/setup.log" ||
        { cat "$tmp/setup.log"; exit 1; }
    grep -q '^#define VT_HAVE_SUNDIALS 0$' "$tmp/nosun/include/vtdyn/version.h" ||
        { echo "VT_HAVE_SUNDIALS is not 0 in the generated header"; exit 1; }
    tests=(model solve reactions recursive kinematic_solve kinematic_analysis trajectory arena)
    meson compile -C "$tmp/nosun" -j "$jobs" consumer_c99 "${tests[@]/#/test_}" >"$tmp/build.log" ||
        { cat "$tmp/build.log"; exit 1; }
    if grep -q 'NEEDED.*sundials' <<< "$(readelf -d "$tmp/nosun/libvtdyn.so")"; then
        echo "the core built with -Dsundials=disabled still links SUNDIALS"; exit 1
    fi
    if grep -qw vt_dynamic_analysis <<< "$(nm -D --defined-only "$tmp/nosun/libvtdyn.so")"; then
        echo "the core built with -Dsundials=disabled exports vt_dynamic_analysis"; exit 1
    fi
    meson test -C "$tmp/nosun" --no-rebuild --print-errorlogs "${tests[@]}" consume_c99
    ;;
*)
    echo "run.sh: unknown mode '$mode' (pkgconfig, subproject, nosundials)"; exit 2 ;;
esac
