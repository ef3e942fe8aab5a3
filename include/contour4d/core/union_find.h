#pragma once
//! \file union_find.h
//! \brief Disjoint sets with path halving. The smallest index of a set is its root, so results never
//! depend on the order of unions.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace c4d {

//! Index: the element type (std::uint32_t halves the memory where the count fits).
template <class Index>
struct DisjointSets {
  std::vector<Index> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), Index{0}); }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  //! Joins the sets of a and b; false when they were already one.
  bool unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent[std::max(a, b)] = static_cast<Index>(std::min(a, b));
    return true;
  }
};

using UnionFind = DisjointSets<std::size_t>;

}  // namespace c4d
