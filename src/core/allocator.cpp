#include "contour4d/core/allocator.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace c4d {

void keep_freed_memory() {
#if defined(__GLIBC__)
  // Blocks up to 256 MiB from the heap, and the heap trimmed only above 512 MiB free. Peak resident
  // memory stays about that of the largest simultaneous use.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

}  // namespace c4d
