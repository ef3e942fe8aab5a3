#pragma once
//! \file radix_sort.h
//! \brief Sorting (value, id) pairs into std::sort's order by a radix sort: the remeshing's edge lists
//! (tens of thousands of edges by length), where std::sort's comparisons mispredict about every other time.

#include <cstdint>
#include <utility>
#include <vector>

namespace c4d {

//! Sorts `items` into the order std::sort gives them (by the double, −0 equal to +0, then by the id),
//! whatever their number; `spare` is working memory, reused across calls. A stable least-significant-
//! byte radix sort of the doubles' bits (bytes where every item agrees skipped), then each run of equal
//! doubles sorted by id. Where no two items compare equal unless identical, the result is that of
//! std::sort bit for bit. \pre no NaN among the doubles.
void sort_pairs(std::vector<std::pair<double, std::uint64_t>>& items,
                std::vector<std::pair<double, std::uint64_t>>& spare);

}  // namespace c4d
