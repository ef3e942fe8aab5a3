#pragma once
//! \file connectivity.h
//! \brief Tree-based connectivity (Lim et al. 2014, "Tree-Based Connectivity"): above/below links
//! between contours of adjacent slices of one frame, prev/next links between contours of one slice
//! in adjacent frames. Weak links (similarity ≤ threshold) are dropped, then Kruskal's algorithm
//! completes the kept links into one tree per structure.

#include <vector>

#include "contour4d/core/stack.h"

namespace c4d {

//! One link between two contours. Contours are named by frame index, slice id (Slice::id) and
//! index in Slice::contours. For intra-frame links slice_a lies below slice_b (smaller offset);
//! for inter-frame links frame_b == frame_a + 1.
struct Connection {
  int frame_a = 0, slice_a = 0, contour_a = 0;
  int frame_b = 0, slice_b = 0, contour_b = 0;
  double similarity = 0.0;        //!< eq. 5, in [0, 1]
  bool kept_by_threshold = true;  //!< true: over the threshold; false: added by Kruskal to connect the tree
};

//! Options of the connectivity stage.
struct ConnectivityOptions {
  double threshold = 0.3;       //!< links with similarity above this are fixed (paper: 30 %)
  bool complete_tree = true;    //!< add weaker links (Kruskal, by decreasing similarity) to join components
  bool respect_nesting = true;  //!< only link contours of equal nesting parity (outer–outer, hole–hole)
};

//! Above/below links of frame `frame`: every pair of contours on adjacent slices (by offset) is
//! scored; pairs over the threshold are kept, then Kruskal adds the strongest remaining pairs with
//! non-zero similarity that join two components. Sorted by (slice_a, contour_a, slice_b, contour_b).
//! \throw InvalidInput when `frame` is out of range.
std::vector<Connection> intra_frame_connections(const Sequence& seq, int frame,
                                                const ConnectivityOptions& options = {});

//! Prev/next links: for every slice id, contours of that slice in frames t and t+1, treated the same
//! way (threshold, then Kruskal over the whole sequence of that slice id).
std::vector<Connection> inter_frame_connections(const Sequence& seq, const ConnectivityOptions& options = {});

//! Nesting depth of each contour of a slice among its neighbours on that slice (0: outermost,
//! 1: hole, 2: island in a hole, ...), from 2D polygons in one plane.
std::vector<int> nesting_depths(const std::vector<std::vector<Vec2>>& polygons);

//! Generic completion used by both functions, exposed for tests: `n` nodes, candidate edges
//! (i, j, weight); edges with weight > threshold are fixed, then the others by decreasing weight
//! (ties: lower (i, j) first) join components. Returns the chosen edge indices, ascending.
struct WeightedEdge {
  int i = 0, j = 0;
  double weight = 0.0;
};
std::vector<int> threshold_then_kruskal(int n, const std::vector<WeightedEdge>& edges, double threshold,
                                        bool complete_tree = true);

}  // namespace c4d
