#pragma once
// The benchmarks' main, as the CLI's (apps/contour4d/main.cpp): freed memory kept for reuse
// (core/allocator.h), then Google Benchmark's own main.
#include <benchmark/benchmark.h>

#include "contour4d/core/allocator.h"

namespace c4d::bench {

inline int run_benchmarks(int argc, char** argv) {
  c4d::keep_freed_memory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace c4d::bench
