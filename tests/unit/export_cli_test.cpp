// `contour4d export` end to end on reconstructions made here (the left-heart cycle phantom, coarse; biv-me
// patient 1, coarse): every target written, read back by independent Python readers (python3-vtk9, meshio,
// numpy) and Debian's OpenFOAM; the same bytes whatever the thread count; the bad inputs of issue 47, each with
// its own exit code and nothing written.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace c4d {
namespace {
namespace fs = std::filesystem;

struct Shell {
  int rc = -1;
  std::string out;
};

Shell shell(const std::string& cmd, const fs::path& log) {
  const int status = std::system((cmd + " > " + log.string() + " 2>&1").c_str());
  Shell r;
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.out = ss.str();
  return r;
}

std::string cli() { return std::string(C4D_CLI); }

class ExportCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("c4d-export-" + std::to_string(::getpid())));
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    const fs::path r = *root_;
    // The left-heart cycle, 10 frames of a 1000 ms cycle, coarse (edge 3 mm).
    ok_ = shell(cli() + " phantom left-heart-cycle --frames 10 -o " + (r / "lh").string(), r / "log.txt").rc == 0 &&
          shell(cli() + " reconstruct " + (r / "lh/contours.json").string() + " --edge 3 --threads 2 -o " +
                    (r / "lh-out").string(),
                r / "log.txt")
                  .rc == 0;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
  }
  void SetUp() override {
    if (!C4D_HEAVY_TESTS) GTEST_SKIP() << "heavy tests are off";
    ASSERT_TRUE(ok_) << "the phantom reconstruction failed";
  }
  static fs::path* root_;
  static bool ok_;
};
fs::path* ExportCli::root_ = nullptr;
bool ExportCli::ok_ = false;

std::string python(const std::string& script, const std::string& args) {
  return std::string(C4D_PYTHON) + " " + std::string(C4D_TEST_SCRIPTS) + "/" + script + " " + args;
}

TEST_F(ExportCli, LeftHeartToEveryTargetReadsBackExactly) {
  const fs::path r = *root_, out = r / "lh-all";
  const Shell e =
      shell(cli() + " export " + (r / "lh-out").string() +
                " --to svfsi --to openfoam --to vampy --steps 20 --cavity-steps --threads 2 -o " + out.string(),
            r / "export.txt");
  ASSERT_EQ(e.rc, 0) << e.out;
  EXPECT_NE(e.out.find("faces: wall inlet outlet"), std::string::npos) << e.out;  // two base ends, apex closed
  for (const char* f :
       {"svfsi/mesh-complete/mesh-complete.mesh.vtu", "svfsi/wall_displacement.dat", "svfsi/inlet_displacement.dat",
        "svfsi/solver.xml", "openfoam/constant/polyMesh/faces", "openfoam/constant/boundaryData/wall/points",
        "openfoam/system/controlDict", "vampy/model.vtp", "vampy/model_moved_20.vtp", "export.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const nlohmann::json rep = nlohmann::json::parse(std::ifstream(out / "export.json"));
  EXPECT_EQ(rep["cavity"]["over_the_cycle"]["inverted"], 0);
  EXPECT_LT(rep["cavity"]["over_the_cycle"]["max_volume_difference_to_surface"].get<double>(), 1e-3);
  const Shell sv =
      shell(python("check_export_svfsi.py", (r / "lh-out").string() + " " + out.string()), r / "svfsi.txt");
  EXPECT_EQ(sv.rc, 0) << sv.out;
  const Shell of =
      shell(python("check_export_openfoam.py", (r / "lh-out").string() + " " + out.string()), r / "foam.txt");
  if (of.rc == 77) GTEST_SKIP() << of.out;
  // 0: all of it; 3: all of it except that OpenFOAM's own displacementLaplacian inverted a few cells on the way
  // (the wall still exact, contour4d's moving cavity valid in checkMesh at every time): a known limit, printed.
  EXPECT_TRUE(of.rc == 0 || of.rc == 3) << of.out;
  std::cout << sv.out << of.out;
}

TEST_F(ExportCli, ListsTheEnds) {
  const Shell e = shell(cli() + " export " + (*root_ / "lh-out").string() + " --list-ends", *root_ / "ends.txt");
  ASSERT_EQ(e.rc, 0) << e.out;
  EXPECT_NE(e.out.find("end 1: base side, inlet"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("end 2: base side, outlet"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("end 3: apex side, apex"), std::string::npos) << e.out;
}

TEST_F(ExportCli, SameBytesWhateverTheThreadCount) {
  const fs::path r = *root_;
  for (int threads : {1, 2})
    ASSERT_EQ(shell(cli() + " export " + (r / "lh-out").string() + " --to svfsi --to vampy --steps 8 --threads " +
                        std::to_string(threads) + " -o " + (r / ("t" + std::to_string(threads))).string(),
                    r / "t.txt")
                  .rc,
              0);
  const Shell diff = shell("diff -r " + (r / "t1").string() + " " + (r / "t2").string(), r / "diff.txt");
  EXPECT_EQ(diff.rc, 0) << diff.out;
}

// Bad input: its own exit code, a message naming the problem, nothing written.
void expect_refused(const fs::path& root, const std::string& args, int code, const std::string& words) {
  const fs::path out = root / "refused";
  fs::remove_all(out);
  const Shell e = shell(cli() + " export " + args + " --to openfoam -o " + out.string(), root / "refused.txt");
  EXPECT_EQ(e.rc, code) << e.out;
  EXPECT_NE(e.out.find(words), std::string::npos) << e.out;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(root))
    EXPECT_EQ(entry.path().filename().string().find(".refused"), std::string::npos) << "a stage was left behind";
}

TEST_F(ExportCli, OneFrameRunIsRefused) {
  const fs::path r = *root_;
  ASSERT_EQ(shell(cli() + " reconstruct " + (r / "lh/contours.json").string() + " --edge 3 --frame 0 -o " +
                      (r / "one").string(),
                  r / "one.txt")
                .rc,
            0);
  expect_refused(r, (r / "one").string(), 29, "one-frame run");
}

TEST_F(ExportCli, MeshesWithoutCorrespondenceAreRefused) {
  expect_refused(*root_, (*root_ / "lh/truth").string(), 25, "does not share frame 0's vertices");
}

TEST_F(ExportCli, OpenSurfaceIsRefused) {
  const fs::path r = *root_;
  ASSERT_EQ(shell(cli() + " reconstruct " + (r / "lh/contours.json").string() + " --edge 3 --cap open -o " +
                      (r / "open").string(),
                  r / "open.txt")
                .rc,
            0);
  expect_refused(r, (r / "open").string(), 30, "the surface is open");
}

TEST_F(ExportCli, UnknownFrameTimesAreRefusedUnlessGiven) {
  const fs::path r = *root_;
  fs::remove_all(r / "untimed");
  fs::copy(r / "lh-out", r / "untimed", fs::copy_options::recursive);
  nlohmann::json rep = nlohmann::json::parse(std::ifstream(r / "untimed/report.json"));
  rep["frame_times"] = {{"source", "unknown"}, {"known", false}};
  std::ofstream(r / "untimed/report.json") << rep.dump(2);
  expect_refused(r, (r / "untimed").string(), 32, "--cycle-ms");
  const Shell ok = shell(cli() + " export " + (r / "untimed").string() + " --cycle-ms 800 --to vampy --steps 4 -o " +
                             (r / "timed").string(),
                         r / "timed.txt");
  EXPECT_EQ(ok.rc, 0) << ok.out;
}

// biv-me patient 1, coarse (edge 3 mm), 25 frames over the 829 ms of the DICOM header's NominalInterval. Its
// basal contour shrinks and vanishes in systole, so the frame-0 border of the base lies off one plane in frames
// 5-13 (up to 10 mm): the band between it and the next contour takes up the flattening, each key frame's cavity is
// untangled, and the whole cycle exports with no inverted tet; the files read back as on the phantom.
TEST_F(ExportCli, BivmeLvCavityMovesThroughTheWholeCycle) {
  const fs::path r = *root_, out = r / "biv-x";
  const fs::path data = fs::path(C4D_DATA_DIR) / "bivme-patient1" / "guidepoints";
  ASSERT_TRUE(fs::exists(data)) << "the shared data folder is missing: " << data;
  ASSERT_EQ(
      shell(cli() + " reconstruct " + data.string() + " --edge 3 --cycle-ms 829 --threads 2 -o " + (r / "biv").string(),
            r / "biv.txt")
          .rc,
      0);
  const Shell ends = shell(cli() + " export " + (r / "biv").string() + " --list-ends", r / "biv-ends.txt");
  EXPECT_NE(ends.out.find("end 1: base side, base"), std::string::npos) << ends.out;
  EXPECT_NE(ends.out.find("end 2: apex side, apex"), std::string::npos) << ends.out;
  const Shell e = shell(cli() + " export " + (r / "biv").string() +
                            " --to svfsi --to openfoam --steps 25 --cavity-steps --threads 2 -o " + out.string(),
                        r / "biv-export.txt");
  ASSERT_EQ(e.rc, 0) << e.out;
  const nlohmann::json rep = nlohmann::json::parse(std::ifstream(out / "export.json"));
  EXPECT_EQ(rep["cavity"]["over_the_cycle"]["inverted"], 0);
  EXPECT_GT(rep["cavity"]["over_the_cycle"]["min_dihedral_deg"].get<double>(), 0.5);
  EXPECT_LT(rep["cavity"]["over_the_cycle"]["max_volume_difference_to_surface"].get<double>(), 1e-3);
  EXPECT_TRUE(rep["ends"][0]["frames_not_flat"].empty()) << rep["ends"][0].dump();
  EXPECT_FALSE(rep["ends"][0]["band_vertices"].empty());
  const Shell sv = shell(python("check_export_svfsi.py", (r / "biv").string() + " " + out.string()), r / "bsv.txt");
  EXPECT_EQ(sv.rc, 0) << sv.out;
  const Shell of =
      shell(python("check_export_openfoam.py", (r / "biv").string() + " " + out.string()), r / "bfoam.txt");
  if (of.rc == 77) GTEST_SKIP() << of.out;
  EXPECT_TRUE(of.rc == 0 || of.rc == 3) << of.out;  // 3: OpenFOAM's own displacementLaplacian inverts cells
  std::cout << e.out << sv.out << of.out;
}

}  // namespace
}  // namespace c4d
