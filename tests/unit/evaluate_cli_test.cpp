// `contour4d evaluate` on meshes written to disk: a correct sequence, and the broken ones
// (a flipped triangle, a hole, a frame with shuffled vertices); exit codes with and without --check.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "contour4d/io/contours_json.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/io/output_dir.h"
#include "metrics_fixtures.h"

namespace c4d {
namespace {
namespace fs = std::filesystem;

struct CliRun {
  int rc = -1;
  std::string out;
};

class EvaluateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("c4d-evaluate-" + std::to_string(::getpid()) + "-" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  // Writes frames into root_/name through the library's writer.
  fs::path write(const std::string& name, const std::vector<TriangleMesh>& meshes) {
    MeshFrames mf;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      mf.meshes.push_back(meshes[i]);
      mf.times_ms.push_back(40.0 * static_cast<double>(i));
    }
    OutputDir out(root_ / name);
    write_mesh_frames(out, mf, "evaluate test");
    out.commit();
    return root_ / name;
  }

  CliRun cli(const std::string& args) {
    const fs::path log = root_ / "stdout.txt";
    const std::string cmd = std::string(C4D_CLI) + " evaluate " + args + " > " + log.string() + " 2>&1";
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    r.out = ss.str();
    return r;
  }

  static std::vector<TriangleMesh> sequence(int n) {
    std::vector<TriangleMesh> v;
    for (int f = 0; f < n; ++f) v.push_back(test::breathe(test::icosphere(20.0, 3), f));
    return v;
  }

  fs::path root_;
};

TEST_F(EvaluateCli, CorrectSequenceHasNoFaultAndWritesJson) {
  const fs::path dir = write("good", sequence(4));
  const CliRun r = cli(dir.string());
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("no faults"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vertex correspondence: yes"), std::string::npos) << r.out;
  std::ifstream in(dir / "evaluation.json");
  ASSERT_TRUE(in) << "evaluate must write OUTDIR/evaluation.json";
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["frames"].size(), 4u);
  EXPECT_EQ(j["frames"][0]["topology"]["genus"], 0);
  EXPECT_TRUE(j["summary"]["topology_ok"].get<bool>());
  EXPECT_EQ(cli(dir.string() + " --check").rc, 0);
  // Same input, same bytes.
  const std::string first = read_file(dir / "evaluation.json");
  cli(dir.string());
  EXPECT_EQ(read_file(dir / "evaluation.json"), first);
}

TEST_F(EvaluateCli, FlippedTriangleIsReported) {
  std::vector<TriangleMesh> frames = sequence(3);
  for (TriangleMesh& m : frames) std::swap(m.triangles[100][1], m.triangles[100][2]);
  const fs::path dir = write("flipped", frames);
  const CliRun r = cli(dir.string() + " --json " + (root_ / "e.json").string());
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("frame 0: 1 triangle oriented against its neighbours"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(root_ / "e.json"));
  EXPECT_FALSE(fs::exists(dir / "evaluation.json"));
  EXPECT_EQ(cli(dir.string() + " --check").rc, 25);
}

TEST_F(EvaluateCli, HoleIsReported) {
  std::vector<TriangleMesh> frames = sequence(2);
  for (TriangleMesh& m : frames) m.triangles.erase(m.triangles.begin() + 7);
  const fs::path dir = write("hole", frames);
  const CliRun r = cli(dir.string());
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("frame 1: 3 boundary edges (a hole)"), std::string::npos) << r.out;
  EXPECT_EQ(cli(dir.string() + " --check").rc, 25);
}

TEST_F(EvaluateCli, ShuffledVerticesAreReported) {
  std::vector<TriangleMesh> frames = sequence(5);
  frames[2] = test::shuffle_vertices(frames[2]);
  const fs::path dir = write("shuffled", frames);
  const CliRun r = cli(dir.string() + " --no-self-intersections");
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("vertex correspondence suspicious: frame 2"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("suspicious: frame 3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vertex correspondence: no"), std::string::npos) << r.out;
  EXPECT_EQ(cli(dir.string() + " --no-self-intersections --check").rc, 25);
}

TEST_F(EvaluateCli, ContoursAndTruthGiveConformityAccuracyAndVolumes) {
  const int rings = 9, per = 48;
  std::vector<TriangleMesh> frames;
  Sequence seq;
  std::vector<Frame> cf;
  for (int f = 0; f < 3; ++f) {
    frames.push_back(test::breathe(test::ring_sphere(20.0, rings, per), f));
    cf.push_back(test::ring_contours(frames.back(), rings, per));
  }
  seq = test::z_sequence(cf);
  const fs::path dir = write("rings", frames);
  const fs::path contours = root_ / "contours.json";
  write_file_atomic(contours, format_contours_json(seq));
  const CliRun r = cli(dir.string() + " --contours " + contours.string() + " --truth " + dir.string());
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("no faults"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Simpson discs: EDV"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(read_file(dir / "evaluation.json"));
  for (const auto& f : j["frames"]) {
    EXPECT_LT(f["conformity"]["max_mm"].get<double>(), 1e-4);
    EXPECT_LT(f["accuracy"]["hausdorff_mm"].get<double>(), 1e-4);
    EXPECT_GT(f["simpson"]["volume_mm3"].get<double>(), 0.0);
  }
}

TEST_F(EvaluateCli, MissingFolderIsAFileError) {
  const CliRun r = cli((root_ / "does-not-exist").string());
  EXPECT_EQ(r.rc, 10) << r.out;
}

}  // namespace
}  // namespace c4d
