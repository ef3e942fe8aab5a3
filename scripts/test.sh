#!/usr/bin/env bash
# Installs what is missing (apt), builds contour4d and runs every test with ctest. Idempotent.
#
#   scripts/test.sh              release build (warnings as errors) + all tests
#   scripts/test.sh --sanitize   the same in a second build folder under ASan+UBSan
#   scripts/test.sh --fuzz [S]   builds the libFuzzer targets (clang) and runs each for S seconds (default 60)
#   scripts/test.sh --all        all three, as CI does
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/setup.sh

if [ ! -d "$root/../shared/data" ]; then
  echo "test.sh: ../shared/data is missing beside the checkout ($root/../shared/data); the real-data tests need it." >&2
  exit 1
fi

run_release=0 run_sanitize=0 run_fuzz=0 fuzz_seconds=60
[ $# -eq 0 ] && run_release=1
while [ $# -gt 0 ]; do
  case "$1" in
    --sanitize) run_sanitize=1 ;;
    --fuzz) run_fuzz=1; if [[ "${2:-}" =~ ^[0-9]+$ ]]; then fuzz_seconds=$2; shift; fi ;;
    --all) run_release=1; run_sanitize=1; run_fuzz=1 ;;
    *) echo "usage: scripts/test.sh [--sanitize] [--fuzz [SECONDS]] [--all]" >&2; exit 2 ;;
  esac
  shift
done

build_and_test() {  # dir, extra cmake args...
  local dir=$1; shift
  cmake -S "$root" -B "$dir" -G Ninja -DC4D_STRICT=ON -DC4D_BUILD_TESTS=ON "$@"
  cmake --build "$dir" -j "$jobs"
  (cd "$dir" && ctest --output-on-failure -j "$jobs" --timeout 900)
}

if [ $run_release -eq 1 ]; then
  echo "== release build and tests (build/) =="
  build_and_test "$root/build" -DCMAKE_BUILD_TYPE=Release -DC4D_BUILD_BENCH=ON
fi

if [ $run_sanitize -eq 1 ]; then
  echo "== ASan+UBSan build and tests (build-sanitize/) =="
  # LeakSanitizer is on by default with ASan on Linux; render_test alone turns it off (Mesa, see there).
  export ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp   # Mesa/EGL driver frames only
  # Warnings are errors in the release build; GCC 12 under ASan warns falsely inside libstdc++ (<regex>).
  build_and_test "$root/build-sanitize" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DC4D_SANITIZE=ON -DC4D_BUILD_BENCH=OFF -DC4D_BUILD_PYTHON=OFF -DC4D_STRICT=OFF \
    -DC4D_HEAVY_TESTS=OFF
fi

if [ $run_fuzz -eq 1 ]; then
  echo "== libFuzzer targets, ${fuzz_seconds}s each (build-fuzz/) =="
  CC=clang CXX=clang++ cmake -S "$root" -B "$root/build-fuzz" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DC4D_BUILD_FUZZ=ON -DC4D_BUILD_TESTS=OFF -DC4D_BUILD_BENCH=OFF
  cmake --build "$root/build-fuzz" -j "$jobs"
  for f in "$root"/build-fuzz/tests/fuzz/fuzz_*; do
    [ -x "$f" ] || continue
    name=$(basename "$f")
    corpus_seed="$root/tests/corpus/${name#fuzz_}"
    work=$(mktemp -d)
    [ -d "$corpus_seed" ] && cp -r "$corpus_seed"/. "$work"/ 2>/dev/null || true
    echo "-- $name"
    "$f" -max_total_time="$fuzz_seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 "$work" 2>&1 | tail -n 12
    rm -rf "$work"
  done
  # The label-image reader goes through ITK (GCC only): mutation driver from the sanitizer build.
  export ASAN_OPTIONS=abort_on_error=1 LSAN_OPTIONS=suppressions=$root/tests/lsan.supp
  if [ -x "$root/build-sanitize/tests/fuzz_images_mutate" ]; then
    echo "-- fuzz_images (mutation driver, ASan+UBSan)"
    # ITK prints a warning for most malformed inputs: keep them in a log, show the result.
    work=$(mktemp -d)
    if ! (cd "$work" && "$root/build-sanitize/tests/fuzz_images_mutate" -max_total_time="$fuzz_seconds" -timeout=20 \
          "$root/tests/corpus/images" > "$work/fuzz_images.log" 2>&1); then
      tail -n 80 "$work/fuzz_images.log"
      echo "fuzz_images failed: input kept in $work (timeout-input.bin for a hang)" >&2
      exit 1
    fi
    grep -a "mutation driver" "$work/fuzz_images.log"
    rm -rf "$work"
  else
    echo "-- fuzz_images skipped: run scripts/test.sh --sanitize first (it builds build-sanitize/tests/fuzz_images_mutate)"
  fi
fi
