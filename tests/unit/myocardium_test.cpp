// The output gate on shapes that used to pass as "done" while broken, and the all-frames stage on
// myocardial walls (issue: frames collapsing onto the other wall): a family of
// myocardium-shell label masks (tests/python/make_myocardium.py: walls 5–10 mm, cavity closing towards
// the apex, contraction up to 35 %, tilted stacks, drawn from seeds) reconstructed frame by frame with
// --method carry: each run is valid or refused (the output checks: closed, manifold, outward, no crossing
// triangles, volume near Simpson's discs), and the output does not depend on the threads.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "contour4d/metrics/result_check.h"
#include "contour4d/motion/reconstruct4d.h"
#include "contour4d/pipeline/input.h"

namespace {

int sh(const std::string& cmd) {
  const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string make_mask(const std::string& dir, int seed, int frames) {
  const std::string mask = dir + "/myo" + std::to_string(seed) + ".nii.gz";
  const std::string cmd = std::string(C4D_PYTHON) + " " + C4D_TEST_SCRIPTS + "/make_myocardium.py " + mask +
                          " --seed " + std::to_string(seed) + " --frames " + std::to_string(frames);
  EXPECT_EQ(sh(cmd), 0) << cmd;
  return mask;
}

// Seeds 1–8 (4 frames each): every run is either valid (exit 0, and `evaluate --check` agrees) or refused
// with exit code 26 and nothing written; never a broken result reported as done. Today 5 of the 8 are
// carried valid (docs/algorithms/carry.md): fewer is a regression.
TEST(Myocardium, FamilyIsValidOrRefused) {
  if (!C4D_HEAVY_TESTS) GTEST_SKIP() << "whole-pipeline family: release build only";
  const std::string cli = C4D_CLI;
  int valid = 0;
  for (int seed = 1; seed <= 8; ++seed) {
    const std::string dir = ::testing::TempDir() + "c4d-myo-" + std::to_string(seed);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string mask = make_mask(dir, seed, 4);
    const int rc = sh(cli + " reconstruct " + mask + " --label 2 --method carry -o " + dir + "/out");
    if (rc == 0) {
      ++valid;
      EXPECT_EQ(sh(cli + " evaluate " + dir + "/out --check"), 0) << "seed " << seed;
    } else {
      EXPECT_EQ(rc, 26) << "seed " << seed;
      EXPECT_FALSE(std::filesystem::exists(dir + "/out")) << "seed " << seed;
    }
  }
  EXPECT_GE(valid, 5);
}

// The default all-frames stage (AllFramesMethod::Auto: every frame on the plan's mesh, frames where the cavity
// closes above a slice carried from the nearest rebuilt one) on seeds 1–8: every frame passes the output
// checks in at least 7 of the 8 (docs/algorithms/rebuild.md; seed 8 is refused today), each in seconds.
TEST(Myocardium, RebuiltFamilyPassesTheChecks) {
  if (!C4D_HEAVY_TESTS) GTEST_SKIP() << "whole-pipeline family: release build only";
  int valid = 0;
  for (int seed = 1; seed <= 8; ++seed) {
    const std::string dir = ::testing::TempDir() + "c4d-myo-auto-" + std::to_string(seed);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    c4d::InputOptions in;
    in.label = "2";
    const c4d::Sequence seq = c4d::read_contours(make_mask(dir, seed, 4), in).sequence;
    const c4d::MeshSequence m = c4d::reconstruct_4d(seq);
    const c4d::ResultCheck check = c4d::check_result(m, seq);
    valid += check.ok() ? 1 : 0;
    std::filesystem::remove_all(dir);
  }
  EXPECT_GE(valid, 7);
}

TEST(Myocardium, CarryIsByteIdenticalAtOneAndTwoThreads) {
  const std::string dir = ::testing::TempDir() + "c4d-myo-threads";
  std::filesystem::create_directories(dir);
  const std::string mask = make_mask(dir, 3, 4);
  const std::string cli = C4D_CLI;
  ASSERT_EQ(sh(cli + " reconstruct " + mask + " --label 2 --method carry --threads 1 -o " + dir + "/t1"), 0);
  ASSERT_EQ(sh(cli + " reconstruct " + mask + " --label 2 --method carry --threads 2 -o " + dir + "/t2"), 0);
  for (int f = 0; f < 4; ++f) {
    const std::string name = "/frames/frame_00" + std::to_string(f) + ".vtp";
    EXPECT_EQ(slurp(dir + "/t1" + name), slurp(dir + "/t2" + name)) << name;
  }
  EXPECT_EQ(slurp(dir + "/t1/report.json"), slurp(dir + "/t2/report.json"));
}

// A torus tilted 10° against the slice normal (holes appear and vanish between slices): one valid surface of
// genus 1 (the ring opens into a C-shaped section on the slices above and below, join_opening_holes).
TEST(OutputGate, TiltedTorusIsOneValidGenusOneSurface) {
  const std::string dir = ::testing::TempDir() + "c4d-gate-torus";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string mask = dir + "/torus.nii.gz";
  ASSERT_EQ(sh(std::string(C4D_PYTHON) + " " + C4D_TEST_SCRIPTS + "/make_torus.py " + mask + " --tilt 10"), 0);
  const std::string cli = C4D_CLI;
  ASSERT_EQ(sh(cli + " reconstruct " + mask + " --frame 0 -o " + dir + "/out"), 0);
  ASSERT_EQ(sh(cli + " evaluate " + dir + "/out --check"), 0);
  const auto ev = nlohmann::json::parse(slurp(dir + "/out/evaluation.json"));
  EXPECT_EQ(ev["frames"][0]["topology"]["genus"], 1);
  EXPECT_EQ(ev["frames"][0]["topology"]["components"], 1);
}

}  // namespace
