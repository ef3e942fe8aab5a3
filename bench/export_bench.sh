#!/usr/bin/env bash
# Speed and peak memory of `contour4d export` (issue 47): a reconstruction exported at N steps per cycle with the
# cavity mesh and its motion, on 2 threads, timed by GNU time. Not a test: run by hand or on a schedule.
#
# usage: bench/export_bench.sh BUILD_DIR OUTDIR STEPS [export options...]
#   e.g. bench/export_bench.sh build /tmp/biv 1000 --cycle-ms 829 --to svfsi
set -euo pipefail
build=$1 outdir=$2 steps=$3
shift 3
dest=$(mktemp -d)
trap 'rm -rf "$dest"' EXIT
/usr/bin/time -f "wall %e s, user %U s, peak RSS %M KB" "$build/apps/contour4d/contour4d" export "$outdir" \
  --steps "$steps" --threads 2 -o "$dest/x" "$@" || echo "export exit code $?"
[ -d "$dest/x" ] && du -sh "$dest/x"/* || true
