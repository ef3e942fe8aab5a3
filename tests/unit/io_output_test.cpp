// Round trips of the mesh writers and atomicity of outputs.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "contour4d/core/errors.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/io/obj.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/io/vtk_xml.h"

namespace c4d {
namespace {
namespace fs = std::filesystem;

TriangleMesh tetra(double s = 1.0) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s * std::numbers::pi}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

fs::path temp_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() /
                     ("c4d_test_" + name + "_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(p);
  return p;
}

void expect_same(const TriangleMesh& a, const TriangleMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles, b.triangles);
  for (std::size_t i = 0; i < a.positions.size(); ++i) EXPECT_TRUE(a.positions[i] == b.positions[i]) << i;
}

TEST(Vtp, RoundTripIsExact) {
  const TriangleMesh m = tetra(1.0 / 3.0);
  expect_same(parse_vtp(format_vtp(m), "mem"), m);
  EXPECT_EQ(format_vtp(m), format_vtp(m));
}

TEST(Obj, RoundTripIsExact) {
  const TriangleMesh m = tetra(1.0 / 3.0);
  expect_same(parse_obj(format_obj(m, "test"), "mem"), m);
}

TEST(Vtp, EveryTruncatedPrefixFailsCleanly) {
  const std::string full = format_vtp(tetra());
  for (std::size_t n = 0; n < full.size(); ++n) {
    try {
      (void)parse_vtp(full.substr(0, n), "cut.vtp");
    } catch (const IoError& e) {
      EXPECT_EQ(e.code(), ErrorCode::BadMesh);
    }
  }
}

TEST(Obj, BadIndexNamesTheLine) {
  try {
    (void)parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 3\n", "bad.obj");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.obj: line 3"), std::string::npos) << e.what();
  }
}

TEST(MeshOutput, WritesCollectionAndReadsItBack) {
  const fs::path dir = temp_dir("collection");
  MeshSequence seq;
  const TriangleMesh m = tetra();
  seq.triangles = m.triangles;
  for (int f = 0; f < 3; ++f) {
    auto p = m.positions;
    for (Vec3& v : p) v = v * (1.0 + 0.1 * f);
    seq.positions.push_back(p);
    seq.times_ms.push_back(40.0 * f);
  }
  {
    OutputDir out(dir);
    write_mesh_sequence(out, seq, {}, MeshFormats{.obj = true});
    EXPECT_FALSE(fs::exists(dir / "mesh.pvd"));  // staged, not visible yet
    out.commit();
  }
  ASSERT_TRUE(fs::exists(dir / "frames/frame_002.obj"));
  const MeshFrames back = read_mesh_frames(dir);
  ASSERT_EQ(back.meshes.size(), 3u);
  EXPECT_EQ(back.times_ms[2], 80.0);
  expect_same(back.meshes[1], seq.frame(1));
  fs::remove_all(dir);
}

TEST(OutputDir, UncommittedOutputLeavesNothing) {
  const fs::path dir = temp_dir("uncommitted");
  {
    OutputDir out(dir);
    out.write("a.txt", "x");
  }
  EXPECT_FALSE(fs::exists(dir));
  for (const auto& e : fs::directory_iterator(dir.parent_path()))
    EXPECT_EQ(e.path().filename().string().find("." + dir.filename().string() + ".c4d"), std::string::npos);
}

TEST(OutputDir, CommitReplacesAnEarlierRun) {
  const fs::path dir = temp_dir("replace");
  for (const char* content : {"first", "second"}) {
    OutputDir out(dir);
    out.write("a.txt", content);
    out.commit();
  }
  EXPECT_EQ(read_file(dir / "a.txt"), "second");
  fs::remove_all(dir);
}

TEST(OutputDir, UnwritableDestinationIsReported) {
  try {
    OutputDir out("/proc/c4d-cannot-write-here/out");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(e.code(), ErrorCode::OutputNotWritable);
  }
}

// python3-vtk9, a real VTK client, loads what we write.
TEST(MeshOutput, Python3VtkReadsPvdAndVtp) {
  if (!fs::exists(C4D_PYTHON)) GTEST_FAIL() << "python3 not found at " << C4D_PYTHON << ": run scripts/setup.sh";
  const fs::path dir = temp_dir("vtk");
  MeshFrames frames;
  frames.meshes = {tetra(), tetra(2.0)};
  frames.times_ms = {0.0, 33.5};
  {
    OutputDir out(dir);
    write_mesh_frames(out, frames);
    out.commit();
  }
  const std::string cmd =
      std::string(C4D_PYTHON) + " " + C4D_TEST_SCRIPTS + "/check_vtk_output.py " + dir.string() + " 2 4 4";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace c4d
