// packed_math_internal.h against the scalar std::sqrt and division: the same bits, special values included.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "simd/packed_math_internal.h"

namespace c4d::detail {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::vector<double> samples() {
  std::mt19937_64 rng(7);
  std::vector<double> v{0.0, -0.0, 1.0, 2.0, 0.5, 1e-300, 4.9e-324, 1e300, std::numeric_limits<double>::infinity()};
  std::uniform_real_distribution<double> mant(1.0, 2.0);
  std::uniform_int_distribution<int> ex(-60, 60);
  for (int k = 0; k < 2000; ++k) v.push_back(std::ldexp(mant(rng), ex(rng)));
  return v;
}

TEST(PackedMath, Sqrt2EqualsScalarSqrtBitForBit) {
  const std::vector<double> v = samples();
  for (std::size_t k = 0; k + 1 < v.size(); ++k) {
    double r[2];
    sqrt2(v[k], v[k + 1], r);
    EXPECT_TRUE(same_bits(r[0], std::sqrt(v[k]))) << v[k];
    EXPECT_TRUE(same_bits(r[1], std::sqrt(v[k + 1]))) << v[k + 1];
  }
}

TEST(PackedMath, SqrtOfRatios2EqualsScalarBitForBit) {
  const std::vector<double> v = samples();
  for (std::size_t k = 0; k + 3 < v.size(); ++k) {
    const double a0 = v[k], b0 = v[k + 1], a1 = v[k + 2], b1 = v[k + 3];
    if (b0 == 0 || b1 == 0) continue;  // callers skip such lanes
    double r[2];
    sqrt_of_ratios2(a0, b0, a1, b1, r);
    EXPECT_TRUE(same_bits(r[0], std::sqrt(a0 / b0))) << a0 << " / " << b0;
    EXPECT_TRUE(same_bits(r[1], std::sqrt(a1 / b1))) << a1 << " / " << b1;
  }
}

}  // namespace
}  // namespace c4d::detail
