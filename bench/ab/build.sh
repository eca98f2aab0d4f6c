#!/bin/sh
# Builds one tree's vtdyn into a self-contained shared object for the A/B driver.
# usage: build.sh <tree> <out.so>
# The tree's libvtdyn.a (meson, release, -march=native or $VT_AB_MARCH, no SUNDIALS: the project's release
# benchmark flags) + bench/ab/ab_entry.c + the tree's examples/scenes.c, both compiled with the
# same flags against the tree's headers, -fvisibility=hidden; linked with --exclude-libs,ALL and
# -Bsymbolic so that only ab_setup/ab_batch/ab_check are exported and every vtdyn call binds
# inside the object: two such objects dlopen'ed RTLD_LOCAL share no vtdyn symbol. LAPACK, BLAS
# and libm stay dynamic (the same ones for both builds).
set -eu
[ $# -eq 2 ] || { echo "usage: $0 <tree> <out.so>" >&2; exit 2; }
tree=$(cd "$1" && pwd)
out=$2
here=$(cd "$(dirname "$0")" && pwd)
cc=${CC:-cc}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# VT_AB_MARCH=x86-64-v3 where valgrind cannot decode the host's own instructions (AVX-512)
march=${VT_AB_MARCH:-native}

meson setup "$tmp/b" "$tree" --buildtype=release -Dc_args=-march=$march -Dsundials=disabled \
    >"$tmp/setup.log" 2>&1 || { cat "$tmp/setup.log" >&2; echo "build.sh: meson setup failed for $tree" >&2; exit 1; }
ninja -C "$tmp/b" libvtdyn.a >"$tmp/ninja.log" 2>&1 || { tail -40 "$tmp/ninja.log" >&2; echo "build.sh: libvtdyn.a failed for $tree" >&2; exit 1; }

# the scene builders this tree's scenes.h declares (a declaration at the start of a line)
have=""
for f in vt_scene_chain vt_scene_double_link vt_scene_fourbar vt_scene_fourbar_rusr vt_scene_five_link \
         vt_scene_delta_ik vt_scene_stewart vt_scene_knee; do
    if grep -Eq "^[A-Za-z_][A-Za-z0-9_ ]*[ *]$f\(" "$tree/examples/scenes.h"; then have="$have -DAB_HAVE_$f"; fi
done

flags="-std=c11 -O3 -march=$march -fPIC -fvisibility=hidden -I$tree/include -I$tmp/b/include -I$tree/examples"
# shellcheck disable=SC2086
$cc $flags $have -c "$here/ab_entry.c" -o "$tmp/ab_entry.o"
# shellcheck disable=SC2086
$cc $flags -c "$tree/examples/scenes.c" -o "$tmp/scenes.o"
$cc -shared -o "$out" "$tmp/ab_entry.o" "$tmp/scenes.o" "$tmp/b/libvtdyn.a" \
    -Wl,--exclude-libs,ALL -Wl,-Bsymbolic -Wl,-z,defs -llapack -lblas -lm

exported=$(nm -D --defined-only "$out" | awk '{print $3}' | sort | tr '\n' ' ')
if [ "$exported" != "ab_batch ab_check ab_setup " ]; then
    echo "build.sh: $out exports more than ab_*: $exported" >&2
    exit 1
fi
echo "built $out from $tree (exports: $exported; scenes:$(echo "$have" | sed 's/-DAB_HAVE_vt_scene_/ /g'))"
