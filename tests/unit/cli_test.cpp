// The command line as a user meets it: help that teaches by example, distinct exit codes.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>

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
    EXPECT_NE(r.out.find("contour4d " + std::string(sub)), std::string::npos) << sub << " help has no example:\n" << r.out;
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

TEST(Cli, RemesherOptionReachesTheReport) {
  const std::string dir = ::testing::TempDir() + "c4d-cli-remesher";
  ASSERT_EQ(run("phantom bifurcation -o " + dir + "/ph").code, 0);
  const Result r = run("reconstruct " + dir + "/ph/contours.json --frame 0 --remesher fast -o " + dir + "/out");
  EXPECT_EQ(r.code, 0) << r.out;
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen((dir + "/out/report.json").c_str(), "r"), std::fclose);
  ASSERT_TRUE(f);
  std::string report;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), f.get())) report += buf.data();
  EXPECT_NE(report.find("\"remesher\": \"fast\""), std::string::npos);
  EXPECT_EQ(run("reconstruct " + dir + "/ph/contours.json --remesher bogus -o " + dir + "/never").code, 2);
}

}  // namespace
