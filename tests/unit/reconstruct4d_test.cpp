// Properties of the 4D pipeline (Lim et al., "4D Morphing"): one triangle list for every frame,
// every frame closed and through its contours, volumes following the truth, output independent of
// the thread count.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "contour4d/core/errors.h"
#include "contour4d/io/contours_json.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/metrics/conformity.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/motion/morph.h"
#include "contour4d/motion/reconstruct4d.h"
#include "contour4d/phantoms/phantom.h"

namespace c4d {
namespace {
namespace fs = std::filesystem;

Phantom small_ellipsoid() {
  PhantomOptions o;
  o.frames = 5;
  o.truth_edge = 1.0;
  return make_phantom("ellipsoid", o);
}

TEST(Reconstruct4D, EveryFrameIsClosedThroughItsContoursWithOneTriangleList) {
  const Phantom p = small_ellipsoid();
  Reconstruct4DReport rep;
  const MeshSequence m = reconstruct_4d(p.contours, {}, &rep);
  ASSERT_EQ(m.positions.size(), p.contours.frames.size());
  for (std::size_t f = 0; f < m.positions.size(); ++f) {
    ASSERT_EQ(m.positions[f].size(), m.positions[0].size());
    const TriangleMesh mesh = m.frame(f);
    TopologyOptions to;
    to.self_intersections = C4D_HEAVY_TESTS != 0;
    const TopologyReport t = check_topology(mesh, to);
    EXPECT_TRUE(t.faults.empty()) << "frame " << f << ": " << (t.faults.empty() ? "" : t.faults.front());
    EXPECT_EQ(t.genus, 0) << f;
    EXPECT_GT(t.signed_volume, 0) << f;
    const DistanceStats c = contour_conformity(mesh, p.contours.frames[f]);
    EXPECT_LT(c.mean, 0.05) << "frame " << f;
    EXPECT_NEAR(signed_volume(mesh) / p.true_volume_mm3[f], 1.0, 0.03) << "frame " << f;
  }
}

TEST(Reconstruct4D, SubMeshLifetimesFollowContourCounts) {
  Sequence s;
  s.frames.resize(4);
  auto add = [&](int f, int id, double off, int n) {
    Slice sl;
    sl.id = id;
    sl.offset = off;
    sl.contours.resize(static_cast<std::size_t>(n));
    s.frames[static_cast<std::size_t>(f)].slices.push_back(sl);
  };
  for (int f = 0; f < 4; ++f) {
    add(f, 0, 0.0, 1);
    add(f, 1, 5.0, f < 2 ? 1 : 2);  // splits at frame 2
  }
  const auto life = submesh_lifetimes(s);
  ASSERT_EQ(life.size(), 2u);
  EXPECT_EQ(life[0].first_frame, 0);
  EXPECT_EQ(life[0].last_frame, 1);
  EXPECT_EQ(life[1].first_frame, 2);
  EXPECT_EQ(life[1].contours_above, 2);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A fresh temporary folder holding the phantom's contours as c.json.
fs::path folder_with_contours(const Phantom& p, const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("c4d_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_file_atomic(dir / "c.json", format_contours_json(p.contours));
  return dir;
}

// `contour4d reconstruct DIR/c.json -o DIR/OUT EXTRA`; the shell command when it fails, else empty.
std::string reconstruct_cli(const fs::path& dir, const std::string& out, const std::string& extra = "") {
  const std::string cmd = std::string(C4D_CLI) + " reconstruct " + (dir / "c.json").string() + " -o " +
                          (dir / out).string() + " " + extra + " > /dev/null";
  return std::system(cmd.c_str()) == 0 ? std::string() : cmd;
}

// DEVELOPERS.md rule 4: byte-identical output whatever the thread count.
TEST(Reconstruct4D, OutputIsByteIdenticalAtOneTwoAndSixteenThreads) {
  const fs::path dir = folder_with_contours(small_ellipsoid(), "threads");
  for (int t : {1, 2, 16})
    ASSERT_EQ(reconstruct_cli(dir, "out" + std::to_string(t), "--threads " + std::to_string(t)), "");
  for (const char* other : {"out2", "out16"})
    for (const auto& e : fs::recursive_directory_iterator(dir / "out1")) {
      if (!e.is_regular_file()) continue;
      EXPECT_EQ(slurp(e.path()), slurp(dir / other / fs::relative(e.path(), dir / "out1"))) << e.path() << " " << other;
    }
  fs::remove_all(dir);
}

// The frames' surfaces are built while the morph runs: whatever the thread count and scheduling, a run
// with two bad frames fails naming the lower one (OutputIsByteIdenticalAtOneTwoAndSixteenThreads checks the meshes).
TEST(Reconstruct4D, FailingFramesAreReportedLowestFirstWhateverTheThreads) {
  Phantom p = small_ellipsoid();
  for (std::size_t f : {2u, 4u})
    for (Slice& s : p.contours.frames[f].slices) s.contours.clear();
  for (int threads : {1, 2, 4}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    try {
      reconstruct_4d(p.contours);
      ADD_FAILURE() << "frames 2 and 4 have no contour, yet the run succeeded at " << threads << " threads";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.where().frame, 2) << threads << " threads: " << e.what();
      EXPECT_EQ(e.code(), ErrorCode::EmptyFrame) << e.what();
    }
  }
}

// report.json per frame (docs/cli.md): the morph's figures, and the frames' own surfaces, which after frame 0
// are only projection targets and not tested for self-intersections (null, not false).
TEST(Reconstruct4D, ReportListsTheMorphFiguresPerFrame) {
  const Phantom p = small_ellipsoid();
  const fs::path dir = folder_with_contours(p, "report");
  ASSERT_EQ(reconstruct_cli(dir, "out", "--method rbf-project"), "");
  const nlohmann::json r = nlohmann::json::parse(slurp(dir / "out" / "report.json"));
  const auto& frames = r.at("frames");
  ASSERT_EQ(frames.size(), p.contours.frames.size());
  EXPECT_TRUE(frames[0].at("surface").at("self_intersects").is_boolean());
  long slid = 0;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    EXPECT_TRUE(frames[f].at("surface").at("self_intersects").is_null()) << f;
    EXPECT_TRUE(frames[f].at("redone").is_boolean()) << f;
    slid += frames[f].at("sliding_contour_vertices").get<long>();
    EXPECT_TRUE(frames[f].at("plane_snapped_vertices").is_number_integer()) << f;
    const auto& fit = frames[f].at("contour_fit");
    EXPECT_TRUE(fit.at("moved_vertices").is_number_integer()) << f;
    EXPECT_LE(fit.at("max_distance_after_mm").get<double>(), fit.at("max_distance_before_mm").get<double>() + 1e-12)
        << f;
  }
  EXPECT_GT(slid, 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace c4d

namespace c4d {
namespace {

// The paper's sine vertical pre-deformation (opt-in) on the idealized left heart, whose sections
// split and merge between ED and ES: the run stays valid — one triangle list, every frame closed,
// outward, through its contours.
TEST(Reconstruct4D, VerticalDeformationKeepsEveryFrameValidOnTheLeftHeart) {
  PhantomOptions po;
  po.truth_edge = 2.0;
  const Phantom p = make_phantom("left-heart", po);
  Reconstruct4DOptions o;
  o.morph.vertical_deformation = true;
  const MeshSequence m = reconstruct_4d(p.contours, o);
  ASSERT_EQ(m.positions.size(), 3u);
  for (std::size_t f = 0; f < m.positions.size(); ++f) {
    const TriangleMesh mesh = m.frame(f);
    const TopologyReport t = check_topology(mesh, {});
    EXPECT_TRUE(t.faults.empty()) << "frame " << f << ": " << (t.faults.empty() ? "" : t.faults.front());
    EXPECT_GT(t.signed_volume, 0) << f;
    EXPECT_LT(contour_conformity(mesh, p.contours.frames[f]).mean, 0.05) << "frame " << f;
  }
}

}  // namespace
}  // namespace c4d
