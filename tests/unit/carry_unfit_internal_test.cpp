// White-box test of the all-frames run's last repair (motion/carry_unfit_internal.h): a frame left with
// crossing triangles is carried again from a neighbour in the cycle that has none.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "contour4d/metrics/topology.h"
#include "contour4d/motion/reconstruct4d.h"
#include "contour4d/phantoms/phantom.h"
#include "motion/carry_unfit_internal.h"

namespace c4d {
namespace {

// The 5-frame ellipsoid cycle's frame 2 with one vertex thrown through the body to the far wall (its triangles
// then cross the opposite side, as a fold the morph or a carry could not undo leaves them): frame 2 comes back
// without crossings, carried from frame 3, close to what it was, the same at one thread; every other frame keeps
// its bytes.
TEST(CarryUnfit, AFrameLeftCrossingIsCarriedAgainFromANeighbour) {
  PhantomOptions po;
  po.frames = 5;
  const Phantom p = make_phantom("ellipsoid", po);
  const Reconstruct4DOptions options;
  const MeshSequence clean = reconstruct_4d(p.contours, options);
  MeshSequence m = clean;
  std::vector<Vec3>& x = m.positions[2];
  Vec3 centre{};
  for (const Vec3& v : x) centre += v;
  centre = centre / static_cast<double>(x.size());
  const std::size_t thrown = x.size() / 2;
  x[thrown] = centre + (centre - x[thrown]) * 0.98;
  ASSERT_GT(count_self_intersections(m.frame(2)), 0u);

  MeshSequence one_thread = m;
  Reconstruct4DReport rep, rep_one;
  detail::recarry_all(p.contours, m, nullptr, options, rep);
  {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    detail::recarry_all(p.contours, one_thread, nullptr, options, rep_one);
  }
  EXPECT_EQ(one_thread.positions, m.positions);  // the same bytes at any thread count
  EXPECT_EQ(count_self_intersections(m.frame(2)), 0u);
  ASSERT_EQ(rep.carry.frames.size(), m.positions.size());
  EXPECT_EQ(rep.carry.frames[2].source, 3);
  EXPECT_NEAR(signed_volume(m.frame(2)), signed_volume(clean.frame(2)), 0.01 * signed_volume(clean.frame(2)));
  for (std::size_t f : {0u, 1u, 3u, 4u}) {
    EXPECT_EQ(m.positions[f], clean.positions[f]) << "frame " << f;
    EXPECT_EQ(rep.carry.frames[f].source, -1) << "frame " << f;
  }
}

// Nothing crosses: nothing is carried, nothing moves.
TEST(CarryUnfit, ACleanSequenceIsLeftAlone) {
  PhantomOptions po;
  po.frames = 3;
  const Phantom p = make_phantom("ellipsoid", po);
  const MeshSequence clean = reconstruct_4d(p.contours, {});
  MeshSequence m = clean;
  Reconstruct4DReport rep;
  detail::recarry_all(p.contours, m, nullptr, {}, rep);
  EXPECT_EQ(m.positions, clean.positions);
  EXPECT_TRUE(rep.carry.frames.empty());
}

}  // namespace
}  // namespace c4d
