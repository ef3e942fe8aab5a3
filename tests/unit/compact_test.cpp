// Compact 4D model and model.c4d: error bound, round trips, rigid-motion invariance, corrupt files.
#include "contour4d/temporal/compact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "contour4d/core/errors.h"
#include "contour4d/io/model_c4d.h"
#include "contour4d/temporal/sequence.h"

namespace c4d {
namespace {

double max_error(const MeshSequence& in, const MeshSequence& out, const std::vector<std::uint32_t>& order) {
  double e = 0.0;
  for (std::size_t f = 0; f < in.positions.size(); ++f)
    for (std::size_t v = 0; v < order.size(); ++v) e = std::max(e, distance(out.positions[f][v], in.positions[f][order[v]]));
  return e;
}

TEST(Compact, DecodedWithinToleranceAndSameConnectivity) {
  const MeshSequence seq = synthetic_beating_mesh(4, 12);  // 5120 triangles
  std::vector<std::uint32_t> order;
  CompactStats st;
  CompactOptions opt;
  opt.control_vertices = 150;
  const CompactModel m = compact_encode(seq, opt, &order, &st);
  const MeshSequence out = compact_decode(m);
  ASSERT_EQ(out.positions.size(), seq.positions.size());
  ASSERT_EQ(out.triangles.size(), seq.triangles.size());
  EXPECT_LE(max_error(seq, out, order), opt.tolerance);
  EXPECT_NEAR(st.max_error, max_error(seq, out, order), 1e-9);
  EXPECT_EQ(out.times_ms, seq.times_ms);
  // Same triangles up to the vertex permutation (and triangle order): compare as sorted sets.
  std::vector<std::array<std::uint32_t, 3>> a, b;
  for (const Triangle& t : seq.triangles) {
    std::array<std::uint32_t, 3> x = t;
    std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    a.push_back(x);
  }
  for (const Triangle& t : out.triangles) {
    std::array<std::uint32_t, 3> x{order[t[0]], order[t[1]], order[t[2]]};
    std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    b.push_back(x);
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  // Orientation kept: the volume of each frame matches.
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    EXPECT_NEAR(signed_volume(out.frame(f)), signed_volume(seq.frame(f)), 1e-3 * signed_volume(seq.frame(f)));
}

TEST(Compact, TighterToleranceHolds) {
  const MeshSequence seq = synthetic_beating_mesh(3, 8);
  for (double tol : {0.2, 0.05, 0.01}) {
    CompactOptions opt;
    opt.tolerance = tol;
    opt.control_vertices = 60;
    std::vector<std::uint32_t> order;
    const MeshSequence out = compact_decode(compact_encode(seq, opt, &order));
    EXPECT_LE(max_error(seq, out, order), tol) << "tolerance " << tol;
  }
}

TEST(Compact, WithoutReorderKeepsIds) {
  const MeshSequence seq = synthetic_beating_mesh(3, 6);
  CompactOptions opt;
  opt.reorder = false;
  const MeshSequence out = compact_decode(compact_encode(seq, opt));
  // The index codec may rotate a triangle's corners (winding kept) but keeps the triangle order.
  ASSERT_EQ(out.triangles.size(), seq.triangles.size());
  for (std::size_t t = 0; t < seq.triangles.size(); ++t) {
    Triangle a = seq.triangles[t], b = out.triangles[t];
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    std::rotate(b.begin(), std::min_element(b.begin(), b.end()), b.end());
    EXPECT_EQ(a, b) << t;
  }
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    for (std::size_t v = 0; v < seq.positions[f].size(); ++v) EXPECT_LE(distance(out.positions[f][v], seq.positions[f][v]), opt.tolerance);
}

TEST(Compact, RigidMotionInvariantError) {
  MeshSequence seq = synthetic_beating_mesh(3, 6);
  MeshSequence moved = seq;
  const double c = std::cos(0.7), s = std::sin(0.7);
  for (auto& frame : moved.positions)
    for (Vec3& p : frame) p = Vec3{c * p.x - s * p.z + 100.0, p.y - 50.0, s * p.x + c * p.z + 7.0};
  for (const MeshSequence* q : {&seq, &moved}) {
    std::vector<std::uint32_t> order;
    const MeshSequence out = compact_decode(compact_encode(*q, {}, &order));
    EXPECT_LE(max_error(*q, out, order), 0.05);
  }
}

TEST(Compact, DeterministicBytes) {
  const MeshSequence seq = synthetic_beating_mesh(3, 5);
  EXPECT_EQ(serialize_model_c4d(compact_encode(seq)), serialize_model_c4d(compact_encode(seq)));
}

TEST(Compact, FileRoundTripAndCorruption) {
  const MeshSequence seq = synthetic_beating_mesh(2, 4);
  const CompactModel m = compact_encode(seq);
  const std::string bytes = serialize_model_c4d(m);
  const CompactModel back = parse_model_c4d(bytes);
  EXPECT_EQ(serialize_model_c4d(back), bytes);
  // Every truncated prefix fails cleanly.
  for (std::size_t n = 0; n < bytes.size(); n += 7) EXPECT_THROW(parse_model_c4d(bytes.substr(0, n)), IoError) << n;
  // A flipped payload bit fails the checksum.
  std::string bad = bytes;
  bad[bad.size() / 2] = static_cast<char>(bad[bad.size() / 2] ^ 0x10);
  EXPECT_THROW(parse_model_c4d(bad), IoError);
  std::string wrong = bytes;
  wrong[0] = 'X';
  try {
    parse_model_c4d(wrong);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(e.code(), ErrorCode::Format);
  }
}

TEST(Compact, RejectsInconsistentFrames) {
  MeshSequence seq = synthetic_beating_mesh(1, 3);
  seq.positions[2].pop_back();
  EXPECT_THROW(compact_encode(seq), InvalidInput);
  MeshFrames frames;
  const MeshSequence good = synthetic_beating_mesh(1, 2);
  frames.meshes = {good.frame(0), good.frame(1)};
  frames.meshes[1].triangles[0] = {0, 2, 1};
  frames.times_ms = {0, 1};
  EXPECT_THROW(to_mesh_sequence(frames, "x"), InvalidInput);
}

}  // namespace
}  // namespace c4d
