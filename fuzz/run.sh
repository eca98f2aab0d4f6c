#!/usr/bin/env bash
# Builds the libFuzzer harness (clang, with AddressSanitizer and UndefinedBehaviorSanitizer
# over the library too) into build-fuzz/ and runs it on fuzz/corpus for the given seconds
# (default 60). Needs clang and libclang-rt-14-dev (VT_SETUP_EXTRA="clang libclang-rt-14-dev"
# tools/setup installs them). Exits non-zero on a crash or a sanitizer report.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
out=build-fuzz
mkdir -p "$out/corpus"
flags="-g -O1 -std=c11 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -Iinclude"
clang $flags src/*.c fuzz/fuzz_model.c -o "$out/fuzz_model" \
    -lsundials_ida -lsundials_nvecserial -lsundials_sunmatrixdense -lsundials_sunlinsoldense \
    -llapack -lblas -lm
# a fresh copy of the seed corpus: new inputs go to build-fuzz/corpus, the repository stays clean
cp fuzz/corpus/* "$out/corpus/" 2>/dev/null || true
"$out/fuzz_model" -max_total_time="$seconds" -print_final_stats=1 -rss_limit_mb=4096 "$out/corpus" 2>&1 | tail -25
