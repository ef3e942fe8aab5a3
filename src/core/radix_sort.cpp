// Radix sort of (value, id) pairs (radix_sort.h): not from the papers; the remeshing's edge lists
// (Lim et al. 2014, "Surface Smoothing and Refinement") are sorted with it.
#include "contour4d/core/radix_sort.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace c4d {
namespace {

// A double's bits turned so that they compare as the doubles do (−0 as +0).
std::uint64_t ordered_bits(double d) {
  std::uint64_t u = 0;
  std::memcpy(&u, &d, sizeof u);
  constexpr std::uint64_t kSign = std::uint64_t{1} << 63;
  if (u == kSign) u = 0;
  return (u & kSign) != 0 ? ~u : u | kSign;
}

}  // namespace

void sort_pairs(std::vector<std::pair<double, std::uint64_t>>& items,
                std::vector<std::pair<double, std::uint64_t>>& spare) {
  const std::size_t n = items.size();
  if (n < 512 || n > UINT32_MAX) {  // short lists: std::sort is as fast
    std::sort(items.begin(), items.end());
    return;
  }
  std::vector<std::uint64_t> bits(n), bits_spare(n);
  std::array<std::array<std::uint32_t, 256>, 8> count{};
  for (std::size_t i = 0; i < n; ++i) {
    bits[i] = ordered_bits(items[i].first);
    for (std::size_t b = 0; b < 8; ++b) ++count[b][(bits[i] >> (8 * b)) & 0xffu];
  }
  spare.resize(n);
  for (std::size_t b = 0; b < 8; ++b) {
    auto& c = count[b];
    if (c[(bits[0] >> (8 * b)) & 0xffu] == n) continue;  // every item in one bucket: nothing moves
    std::uint32_t sum = 0;
    for (auto& k : c) {
      const std::uint32_t here = k;
      k = sum;
      sum += here;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t to = c[(bits[i] >> (8 * b)) & 0xffu]++;
      spare[to] = items[i];
      bits_spare[to] = bits[i];
    }
    items.swap(spare);
    bits.swap(bits_spare);
  }
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && bits[j] == bits[i]) ++j;
    if (j - i > 1)
      std::sort(items.begin() + static_cast<std::ptrdiff_t>(i), items.begin() + static_cast<std::ptrdiff_t>(j));
    i = j;
  }
}

}  // namespace c4d
