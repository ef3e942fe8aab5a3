// A deliberately wrong include: another folder's private header.
#include "../core/avx_internal.h"
// And hand-written SIMD outside src/simd/.
#include <immintrin.h>
