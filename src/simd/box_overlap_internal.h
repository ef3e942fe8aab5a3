#pragma once
// The broad phase of the self-intersection test (metrics/topology.cpp): which boxes of one grid cell overlap
// item a's and share none of its keys (vertex indices), four boxes per SSE2 instruction, with the scalar loop
// that gives the same answer where SSE2 is missing and for the cell's last items.

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace c4d::detail {
namespace {

//! The items of the cells, column by column: loose (float) lower and upper corners and three keys. Each
//! column has three readable entries past its last item: the last four-wide loads reach them (their lanes
//! are masked).
struct BoxColumns {
  const float *lo0, *lo1, *lo2, *hi0, *hi1, *hi2;
  const std::uint32_t *key0, *key1, *key2;
};

//! Calls visit(b) for each item b in [a + 1, e), in increasing order, whose box overlaps a's (closed boxes:
//! not x.lo > y.hi nor y.lo > x.hi in any coordinate) and that has none of a's keys other than `no_key`.
template <class Visit>
void for_each_overlapping(const BoxColumns& c, std::uint32_t a, std::uint32_t e, std::uint32_t no_key, Visit&& visit) {
  const std::uint32_t xk[3] = {c.key0[a], c.key1[a], c.key2[a]};
  std::uint32_t b = a + 1;
#if defined(__SSE2__)
  const __m128 xl0 = _mm_set1_ps(c.lo0[a]), xl1 = _mm_set1_ps(c.lo1[a]), xl2 = _mm_set1_ps(c.lo2[a]);
  const __m128 xh0 = _mm_set1_ps(c.hi0[a]), xh1 = _mm_set1_ps(c.hi1[a]), xh2 = _mm_set1_ps(c.hi2[a]);
  for (; b < e; b += 4) {
    // Not (x.lo > y.hi or y.lo > x.hi) in any coordinate: the scalar test below, lane by lane.
    __m128 keep = _mm_and_ps(_mm_cmpngt_ps(xl0, _mm_loadu_ps(c.hi0 + b)), _mm_cmpngt_ps(_mm_loadu_ps(c.lo0 + b), xh0));
    keep = _mm_and_ps(
        keep, _mm_and_ps(_mm_cmpngt_ps(xl1, _mm_loadu_ps(c.hi1 + b)), _mm_cmpngt_ps(_mm_loadu_ps(c.lo1 + b), xh1)));
    keep = _mm_and_ps(
        keep, _mm_and_ps(_mm_cmpngt_ps(xl2, _mm_loadu_ps(c.hi2 + b)), _mm_cmpngt_ps(_mm_loadu_ps(c.lo2 + b), xh2)));
    int lanes = _mm_movemask_ps(keep) & (e - b >= 4 ? 15 : (1 << (e - b)) - 1);  // items of the cell only
    if (lanes == 0) continue;
    const __m128i y0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(c.key0 + b));
    const __m128i y1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(c.key1 + b));
    const __m128i y2 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(c.key2 + b));
    __m128i shared = _mm_setzero_si128();
    for (std::uint32_t k : xk)
      if (k != no_key) {
        const __m128i v = _mm_set1_epi32(static_cast<int>(k));
        shared = _mm_or_si128(
            shared, _mm_or_si128(_mm_cmpeq_epi32(v, y0), _mm_or_si128(_mm_cmpeq_epi32(v, y1), _mm_cmpeq_epi32(v, y2))));
      }
    lanes &= ~_mm_movemask_ps(_mm_castsi128_ps(shared));
    for (; lanes != 0; lanes &= lanes - 1)
      visit(b + static_cast<std::uint32_t>(__builtin_ctz(static_cast<unsigned>(lanes))));
  }
#endif
  for (; b < e; ++b) {  // without SSE2
    if (c.lo0[a] > c.hi0[b] || c.lo0[b] > c.hi0[a] || c.lo1[a] > c.hi1[b] || c.lo1[b] > c.hi1[a] ||
        c.lo2[a] > c.hi2[b] || c.lo2[b] > c.hi2[a])
      continue;
    bool shared = false;
    for (std::uint32_t k : xk)
      if (k != no_key && (k == c.key0[b] || k == c.key1[b] || k == c.key2[b])) shared = true;
    if (!shared) visit(b);
  }
}

}  // namespace
}  // namespace c4d::detail
