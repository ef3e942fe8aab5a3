#pragma once
//! \file allocator.h
//! \brief Keeps freed memory in the process for reuse (glibc's malloc), for the CLI and the benchmarks.

namespace c4d {

//! Asks the C library's allocator to keep freed memory for the next allocation instead of handing
//! large blocks back to the kernel.
//!
//! glibc's malloc serves blocks above its mmap threshold (128 KiB at first) with fresh mappings and
//! unmaps them when freed, and trims the heap's top once enough of it is free: every such array a stage
//! allocates then comes back as new zeroed pages, each faulted in on first touch (a few percent of a
//! one-frame surface's time). Raising both thresholds lets the stages reuse the
//! memory the stages before them freed. Results do not change (memory contents are never read before
//! they are written). Call once, early in `main`; does nothing where the C library is not glibc.
void keep_freed_memory();

}  // namespace c4d
