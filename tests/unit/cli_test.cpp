// The command line as a user meets it: help that teaches by example, distinct exit codes.
#include <sys/wait.h>

#include <array>
#include <fstream>
#include <iterator>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

struct Result {
  int code = -1;
  std::string out;
};

Result run(const std::string& args) {
  const std::string cmd = std::string(C4D_CLI) + " " + args + " 2>&1";
  Result r;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::array<char, 4096> buf{};
  while (pipe && fgets(buf.data(), buf.size(), pipe.get())) r.out += buf.data();
  const int status = pclose(pipe.release());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST(Cli, TopLevelHelpTeachesByExample) {
  const Result r = run("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* sub : {"reconstruct", "extract", "evaluate", "phantom", "Examples"})
    EXPECT_NE(r.out.find(sub), std::string::npos) << sub << "\n" << r.out;
}

TEST(Cli, EverySubcommandHelpHasExamples) {
  for (const char* sub : {"reconstruct", "extract", "evaluate", "phantom"}) {
    const Result r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("contour4d " + std::string(sub)), std::string::npos) << sub << " help has no example:\n"
                                                                              << r.out;
  }
}

TEST(Cli, UnknownSubcommandIsAUsageError) {
  EXPECT_EQ(run("frobnicate").code, 2);
  EXPECT_EQ(run("").code, 2);
}

TEST(Cli, MissingInputIsNamed) {
  const Result r = run("extract /nonexistent/contours.json -o /tmp/c4d-never.json");
  EXPECT_EQ(r.code, 10);
  EXPECT_NE(r.out.find("/nonexistent/contours.json"), std::string::npos) << r.out;
}

TEST(Cli, TilingOptionReachesTheReport) {
  const std::string dir = ::testing::TempDir() + "c4d-cli-tiling";
  ASSERT_EQ(run("phantom bifurcation -o " + dir + "/ph").code, 0);
  const Result r = run("reconstruct " + dir + "/ph/contours.json --frame 0 --tiling delaunay -o " + dir + "/out");
  EXPECT_EQ(r.code, 0) << r.out;
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen((dir + "/out/report.json").c_str(), "r"), std::fclose);
  ASSERT_TRUE(f);
  std::string report;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), f.get())) report += buf.data();
  EXPECT_NE(report.find("\"tiling\": \"delaunay\""), std::string::npos);
  EXPECT_EQ(run("reconstruct " + dir + "/ph/contours.json --tiling bogus -o " + dir + "/never").code, 2);
}

// A result that fails the output checks: its own exit code, a message naming the frame and the fault,
// no output folder; --keep-failed writes it elsewhere, marked FAILED. (A volume bound no surface can meet
// stands in for a broken frame.)
TEST(Cli, FailedCheckWritesNothingAndHasItsOwnExitCode) {
  const std::string dir = ::testing::TempDir() + "c4d-cli-gate";
  std::filesystem::remove_all(dir);  // a run before this one left its outputs
  ASSERT_EQ(run("phantom left-heart -o " + dir + "/ph").code, 0);
  const std::string in = dir + "/ph/contours.json";
  const Result r = run("reconstruct " + in + " --frame 1 --volume-tolerance 0 -o " + dir + "/out");
  EXPECT_EQ(r.code, 26) << r.out;
  EXPECT_NE(r.out.find("frame 1: volume"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("nothing was written"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  const Result kept =
      run("reconstruct " + in + " --frame 1 --volume-tolerance 0 -o " + dir + "/out --keep-failed " + dir + "/failed");
  EXPECT_EQ(kept.code, 26) << kept.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/failed/FAILED.txt"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/failed/report.json"));
  // The same input within the default bound passes, and the report holds every frame's check.
  const Result ok = run("reconstruct " + in + " --frame 1 -o " + dir + "/out");
  EXPECT_EQ(ok.code, 0) << ok.out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/report.json"));
}

// The front door: report.json opens with a summary (volume curve, ED/ES frames, EDV/ESV/EF); VTP + PVD by
// default, OBJ on request; a bad --format stops before the work; an edge out of proportion to the slices is
// warned about; --help puts the options a user needs first.
TEST(Cli, SummaryFirstFormatsAndWarnings) {
  const std::string dir = ::testing::TempDir() + "c4d-cli-front";
  std::filesystem::remove_all(dir);
  ASSERT_EQ(run("phantom left-heart -o " + dir + "/ph").code, 0);
  const std::string in = dir + "/ph/contours.json";
  const Result r = run("reconstruct " + in + " -o " + dir + "/out");
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream f(dir + "/out/report.json");
  const nlohmann::ordered_json report = nlohmann::ordered_json::parse(f);
  ASSERT_EQ(report.begin().key(), "summary");
  const auto& s = report["summary"];
  ASSERT_EQ(s["volume_ml"].size(), 3u);
  EXPECT_EQ(s["frame_times_ms"].size(), 3u);
  const int ed = s["ed_frame"].get<int>(), es = s["es_frame"].get<int>();
  EXPECT_DOUBLE_EQ(s["edv_ml"].get<double>(), s["volume_ml"][static_cast<std::size_t>(ed)].get<double>());
  EXPECT_DOUBLE_EQ(s["esv_ml"].get<double>(), s["volume_ml"][static_cast<std::size_t>(es)].get<double>());
  EXPECT_GT(s["ef_percent"].get<double>(), 0.0);
  EXPECT_TRUE(s["checks_ok"].get<bool>());
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/frames/frame_000.vtp"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/frames/frame_000.obj"));
  ASSERT_EQ(run("reconstruct " + in + " --frame 0 --format vtp,obj -o " + dir + "/obj").code, 0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/obj/frames/frame_000.obj"));
  const Result bad = run("reconstruct " + in + " --format stl -o " + dir + "/bad");
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("unknown mesh format"), std::string::npos) << bad.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad"));
  const Result coarse = run("reconstruct " + in + " --frame 0 --edge 4 -o " + dir + "/coarse");
  EXPECT_NE(coarse.out.find("is coarse for slices 5.0 mm apart"), std::string::npos) << coarse.out;
  const Result help = run("reconstruct --help");
  const std::size_t edge = help.out.find("--edge"), advanced = help.out.find("Advanced:");
  ASSERT_NE(advanced, std::string::npos) << help.out;
  EXPECT_LT(edge, advanced) << help.out;
  EXPECT_GT(help.out.find("--tiling"), advanced) << help.out;
  std::filesystem::remove_all(dir);
}

// Ctrl-C (SIGINT) in the middle of a run leaves no hidden staging folder beside the output.
TEST(Cli, InterruptLeavesNoStagingFolder) {
  const std::string dir = ::testing::TempDir() + "c4d-cli-sigint";
  std::filesystem::remove_all(dir);
  ASSERT_EQ(run("phantom left-heart-cycle -o " + dir + "/ph").code, 0);
  const std::string cmd = "timeout -s INT 2 " + std::string(C4D_CLI) + " reconstruct " + dir +
                          "/ph/contours.json --threads 1 -o " + dir + "/out >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 124) << "the run ended before the interrupt: make it longer";
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string().front(), '.') << e.path();
  std::filesystem::remove_all(dir);
}

// Every structure in one run: Sunnybrook's endocardium and epicardium, and the wall between them (the
// myocardium), each into OUTDIR/<label>/ with one combined report holding the wall's mass; a structure comes out
// byte for byte as it does alone (--label lv-endo).
TEST(Cli, EveryStructureInOneRun) {
  const std::string dir = ::testing::TempDir() + "c4d-cli-all";
  std::filesystem::remove_all(dir);
  const std::string sb = std::string(C4D_DATA_DIR) + "/sunnybrook-SC-HF-I-1";
  const Result r = run("reconstruct " + sb + " --label all --threads 2 -o " + dir + "/out");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("wall mass"), std::string::npos) << r.out;
  std::ifstream f(dir + "/out/report.json");
  const nlohmann::ordered_json report = nlohmann::ordered_json::parse(f);
  std::vector<std::string> names;
  for (const auto& s : report["summary"]["structures"]) {
    names.push_back(s["name"].get<std::string>());
    EXPECT_TRUE(s["ok"].get<bool>()) << s.dump();
    EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + names.back() + "/report.json")) << names.back();
    if (names.back() == "lv-wall") {
      ASSERT_EQ(s["mass_g"].size(), s["volume_ml"].size());
      const double mass = s["mass_g"][0].get<double>();
      EXPECT_NEAR(mass, 1.05 * s["volume_ml"][0].get<double>(), 1e-3);
      EXPECT_GT(mass, 40.0);  // an adult left ventricle's myocardium: tens to a few hundred grams
      EXPECT_LT(mass, 400.0);
    }
  }
  EXPECT_EQ(names, (std::vector<std::string>{"lv-endo", "lv-epi", "lv-wall"}));
  // The wall alone: one output folder whose summary holds the mass per frame.
  const Result wall = run("reconstruct " + sb + " --label lv-wall -o " + dir + "/wall");
  ASSERT_EQ(wall.code, 0) << wall.out;
  std::ifstream wf(dir + "/wall/report.json");
  const nlohmann::ordered_json wr = nlohmann::ordered_json::parse(wf);
  EXPECT_EQ(wr["summary"]["mass_g"].size(), wr["summary"]["volume_ml"].size());
  // The endocardium alone: the same bytes as in the run of every structure.
  ASSERT_EQ(run("reconstruct " + sb + " --label lv-endo --threads 2 -o " + dir + "/endo").code, 0);
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const char* frame : {"frame_000.vtp", "frame_001.vtp"}) {
    const std::string alone = bytes(dir + "/endo/frames/" + frame);
    EXPECT_FALSE(alone.empty()) << frame;
    EXPECT_TRUE(alone == bytes(dir + "/out/lv-endo/frames/" + frame)) << frame << " differs from --label all's";
  }
  // A structure the input does not hold: refused before any work, nothing written.
  const Result bad = run("reconstruct " + sb + " --label lv-endo --label rv -o " + dir + "/bad");
  EXPECT_EQ(bad.code, 21) << bad.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad"));
  std::filesystem::remove_all(dir);
}

}  // namespace
