// Tests of the input dispatch (include/contour4d/pipeline/input.h) and of `contour4d extract` end to end:
// exit codes per failure class, nothing written on failure.
#include "contour4d/pipeline/input.h"

#include <gtest/gtest.h>

#include "cli_runner.h"
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "contour4d/core/errors.h"
#include "contour4d/io/contours_json.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = C4D_CORPUS_DIR;

ErrorCode code_of(const fs::path& p, const InputOptions& o = {}) {
  try {
    read_contours(p, o);
  } catch (const Error& e) {
    return e.code();
  }
  return static_cast<ErrorCode>(0);
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("c4d_input_test_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Input, DispatchesJsonAndGpFileFolders) {
  const InputResult j = read_contours(kCorpus / "contours_json" / "good_two_slices_two_frames.json");
  EXPECT_EQ(j.format, "contour4d-json");
  EXPECT_EQ(j.sequence.frames.size(), 2u);
  const InputResult g = read_contours(kCorpus / "gpfile" / "good_two_frames_with_lax");
  EXPECT_EQ(g.format, "gpfile");
  EXPECT_FALSE(g.notes.empty());
  const fs::path patient = fs::path(C4D_DATA_DIR) / "bivme-patient1";
  ASSERT_TRUE(fs::is_directory(patient)) << "real data folder missing: " << patient;
  const InputResult p = read_contours(patient);  // parent of guidepoints/
  EXPECT_EQ(p.format, "gpfile");
  EXPECT_EQ(p.sequence.frames.size(), 25u);
}

TEST(Input, Errors) {
  EXPECT_EQ(code_of("/nonexistent/x.json"), ErrorCode::FileNotFound);
  EXPECT_EQ(code_of(kCorpus), ErrorCode::Format);  // a folder without GPFiles
  const fs::path d = temp_dir("errors");
  std::ofstream(d / "contours.csv") << "1,2,3\n";
  EXPECT_EQ(code_of(d / "contours.csv"), ErrorCode::Format);
  fs::remove_all(d);
  // A folder of DICOM images without contours is told so, not "no GPFile".
  const fs::path images = fs::path(C4D_DATA_DIR) / "sunnybrook-SC-HF-I-1" / "dicoms_contoured";
  try {
    read_contours(images);
    ADD_FAILURE() << "a DICOM image folder read as contours";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Format);
    EXPECT_NE(std::string(e.what()).find("DICOM images but no contours"), std::string::npos) << e.what();
  }
}

TEST(Input, LabelSelection) {
  InputOptions o;
  o.label = "lv";
  EXPECT_EQ(read_contours(kCorpus / "contours_json" / "good_two_slices_two_frames.json", o).sequence.frames.size(), 2u);
  o.label = "rv";
  EXPECT_EQ(code_of(kCorpus / "contours_json" / "good_two_slices_two_frames.json", o), ErrorCode::UnknownLabel);
  InputOptions t;
  t.contour_types = {"SAX_LV_ENDOCARDIAL"};
  t.label = "lv-endo";
  EXPECT_EQ(read_contours(kCorpus / "gpfile" / "good_two_frames_with_lax", t).sequence.frames.size(), 2u);
}

using test::run_cli;

TEST(ExtractCli, ExitCodesAndNothingWritten) {
  ASSERT_TRUE(fs::exists(C4D_CLI)) << "CLI not built: " << C4D_CLI;
  const fs::path d = temp_dir("cli");
  const fs::path out = d / "x.json";
  struct Case {
    fs::path input;
    ErrorCode code;
  };
  const Case cases[] = {
      {kCorpus / "contours_json" / "bad_11_empty.json", ErrorCode::EmptyFile},
      {kCorpus / "contours_json" / "bad_12_truncated.json", ErrorCode::Parse},
      {kCorpus / "contours_json" / "bad_14_overflow_1e999.json", ErrorCode::NonFinite},
      {kCorpus / "contours_json" / "bad_16_self_intersecting_bowtie.json", ErrorCode::SelfIntersection},
      {kCorpus / "contours_json" / "bad_19_duplicate_plane.json", ErrorCode::DuplicatePlane},
      {kCorpus / "gpfile" / "bad_22_missing_sliceinfo", ErrorCode::MissingCompanion},
      {d / "missing.json", ErrorCode::FileNotFound},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.input.string());
    EXPECT_EQ(run_cli("extract '" + c.input.string() + "' --strict -o '" + out.string() + "'"),
              static_cast<int>(c.code));
    EXPECT_TRUE(fs::is_empty(d)) << "a failed run left files behind";
  }
  EXPECT_EQ(run_cli("extract '" + (kCorpus / "contours_json" / "good_two_slices_two_frames.json").string() +
                    "' --label nope -o '" + out.string() + "'"),
            static_cast<int>(ErrorCode::UnknownLabel));
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

TEST(ExtractCli, Patient1WritesAReadableDeterministicFile) {
  ASSERT_TRUE(fs::exists(C4D_CLI)) << "CLI not built: " << C4D_CLI;
  const fs::path patient = fs::path(C4D_DATA_DIR) / "bivme-patient1" / "guidepoints";
  ASSERT_TRUE(fs::is_directory(patient)) << "real data folder missing: " << patient;
  const fs::path d = temp_dir("patient");
  ASSERT_EQ(run_cli("extract '" + patient.string() + "' -o '" + (d / "a.json").string() + "'"), 0);
  ASSERT_EQ(run_cli("extract '" + (d / "a.json").string() + "' -o '" + (d / "b.json").string() + "'"), 0);
  const Sequence a = read_contours_json(d / "a.json");
  EXPECT_EQ(a.frames.size(), 25u);
  // Re-extracting the written file gives the same bytes.
  EXPECT_EQ(format_contours_json(a), format_contours_json(read_contours_json(d / "b.json")));
  std::ifstream fa(d / "a.json"), fb(d / "b.json");
  const std::string sa((std::istreambuf_iterator<char>(fa)), {}), sb((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_EQ(sa, sb);
  fs::remove_all(d);
}

// Frame times: the data's own where it has them; --frame-ms / --cycle-ms for inputs without (a label
// image); otherwise the input says they are unknown instead of passing 1 ms steps off as real.
TEST(Input, FrameTimesFromDataOrOptionsOrSaidUnknown) {
  const fs::path dir = fs::path(::testing::TempDir()) / "c4d-input-times";
  fs::remove_all(dir);
  ASSERT_EQ(test::run_cli("phantom ellipsoid --frames 4 -o " + (dir / "ph").string() + " --mask " +
                          (dir / "mask.nii.gz").string()),
            0);
  const fs::path mask = dir / "mask.nii.gz";
  InputResult unknown = read_contours(mask);
  EXPECT_EQ(unknown.timing, "unknown");
  ASSERT_EQ(unknown.sequence.frames.size(), 4u);
  InputOptions o;
  o.frame_ms = 40;
  InputResult by_step = read_contours(mask, o);
  EXPECT_EQ(by_step.timing, "--frame-ms");
  EXPECT_DOUBLE_EQ(by_step.sequence.frames[3].time_ms, 120.0);
  o = {};
  o.cycle_ms = 800;
  InputResult by_cycle = read_contours(mask, o);
  EXPECT_EQ(by_cycle.timing, "--cycle-ms");
  EXPECT_DOUBLE_EQ(by_cycle.sequence.frames[1].time_ms, 200.0);
  // The phantom's contour file has its own times: they win over the option.
  InputResult own = read_contours(dir / "ph" / "contours.json", o);
  EXPECT_EQ(own.timing, "data");
  EXPECT_DOUBLE_EQ(own.sequence.frames[1].time_ms,
                   read_contours(dir / "ph" / "contours.json").sequence.frames[1].time_ms);
  o.frame_ms = 40;
  EXPECT_EQ(code_of(mask, o), ErrorCode::Usage);  // both options at once
}

}  // namespace
}  // namespace c4d
