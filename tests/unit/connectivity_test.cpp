// Tree-based connectivity (Lim et al. 2014): threshold, Kruskal completion, nesting, prev/next.
#include "contour4d/connect/connectivity.h"

#include <gtest/gtest.h>

#include <cmath>

#include "contour4d/core/errors.h"

namespace {

using c4d::Contour;
using c4d::Vec3;

Contour circle(double cx, double cy, double z, double r, int n, int slice) {
  Contour c;
  c.slice = slice;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    c.points.push_back({cx + r * std::cos(a), cy + r * std::sin(a), z});
  }
  return c;
}

c4d::Slice slice(int id, double z, std::vector<Contour> cs) {
  c4d::Slice s;
  s.id = id;
  s.offset = z;
  s.contours = std::move(cs);
  return s;
}

TEST(Connectivity, StackOfCirclesFormsAChain) {
  c4d::Sequence seq;
  seq.frames.resize(1);
  for (int i = 0; i < 5; ++i) seq.frames[0].slices.push_back(slice(i, 5.0 * i, {circle(0, 0, 5.0 * i, 10, 40, i)}));
  const auto links = c4d::intra_frame_connections(seq, 0);
  ASSERT_EQ(links.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(links[i].slice_a, i);
    EXPECT_EQ(links[i].slice_b, i + 1);
    EXPECT_TRUE(links[i].kept_by_threshold);
    EXPECT_NEAR(links[i].similarity, 1.0, 1e-9);
  }
}

TEST(Connectivity, WeakOverlapIsNotFixed) {
  // Figure 5 of the paper: contour 1 of slice 0 grazes contour 0 of slice 1 (about 10 % of perimeter).
  c4d::Sequence seq;
  seq.frames.resize(1);
  seq.frames[0].slices.push_back(slice(0, 0, {circle(0, 0, 0, 10, 64, 0), circle(22, 0, 0, 10, 64, 0)}));
  seq.frames[0].slices.push_back(slice(1, 5, {circle(3, 0, 5, 10, 64, 1), circle(23, 0, 5, 10, 64, 1)}));
  const auto links = c4d::intra_frame_connections(seq, 0);
  int strong = 0, weak = 0;
  for (const auto& l : links) {
    (l.kept_by_threshold ? strong : weak)++;
    if (!l.kept_by_threshold) {
      EXPECT_LE(l.similarity, 0.3);
    }
  }
  EXPECT_EQ(strong, 2);
  // Both structures already hold a strong link; the graze joins the two trees into one (Kruskal) but
  // stays marked as not kept by the threshold. Without completion it is gone.
  EXPECT_EQ(weak, 1);
  c4d::ConnectivityOptions o;
  o.complete_tree = false;
  EXPECT_EQ(c4d::intra_frame_connections(seq, 0, o).size(), 2u);
}

TEST(Connectivity, KruskalKeepsFixedEdgesAndJoinsComponents) {
  // Nodes 0..3; fixed 0-1 (0.9); candidates 1-2 (0.2), 0-2 (0.1), 2-3 (0.25).
  const std::vector<c4d::WeightedEdge> e{{0, 1, 0.9}, {1, 2, 0.2}, {0, 2, 0.1}, {2, 3, 0.25}};
  const auto chosen = c4d::threshold_then_kruskal(4, e, 0.3);
  EXPECT_EQ(chosen, (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(c4d::threshold_then_kruskal(4, e, 0.3, false), (std::vector<int>{0}));
}

TEST(Connectivity, HolesLinkToHolesNotToOuterContours) {
  c4d::Sequence seq;
  seq.frames.resize(1);
  for (int i = 0; i < 3; ++i)
    seq.frames[0].slices.push_back(
        slice(i, 5.0 * i, {circle(0, 0, 5.0 * i, 20, 64, i), circle(0, 0, 5.0 * i, 8, 32, i)}));
  const auto links = c4d::intra_frame_connections(seq, 0);
  ASSERT_EQ(links.size(), 4u);
  for (const auto& l : links) EXPECT_EQ(l.contour_a, l.contour_b);
  const auto depth = c4d::nesting_depths({{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, {{-0.5, -0.5}, {0.5, -0.5}, {0, 0.5}}});
  EXPECT_EQ(depth, (std::vector<int>{0, 1}));
}

TEST(Connectivity, InterFrameLinksFollowTheSliceThroughTime) {
  c4d::Sequence seq;
  seq.frames.resize(3);
  for (int t = 0; t < 3; ++t) {
    std::vector<Contour> cs{circle(t, 0, 0, 10, 40, 7)};
    if (t == 2) cs = {circle(-6, 0, 0, 5, 40, 7), circle(6, 0, 0, 5, 40, 7)};  // topology change
    seq.frames[t].slices.push_back(slice(7, 0.0, cs));
  }
  const auto links = c4d::inter_frame_connections(seq);
  ASSERT_EQ(links.size(), 3u);
  EXPECT_EQ(links[0].frame_a, 0);
  EXPECT_EQ(links[0].frame_b, 1);
  EXPECT_EQ(links[1].frame_b, 2);
  EXPECT_EQ(links[2].frame_b, 2);
  EXPECT_NE(links[1].contour_b, links[2].contour_b);
}

TEST(Connectivity, BadFrameThrows) {
  c4d::Sequence seq;
  EXPECT_THROW(c4d::intra_frame_connections(seq, 0), c4d::InvalidInput);
}

}  // namespace
