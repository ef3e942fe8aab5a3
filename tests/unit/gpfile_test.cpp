// Tests of the biv-me GPFile reader (include/contour4d/io/gpfile.h), on the real patient and on a
// corpus of small broken folders.
#include "contour4d/io/gpfile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "contour4d/core/errors.h"
#include "corpus_check.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

fs::path patient_dir() {
  const fs::path p = fs::path(C4D_DATA_DIR) / "bivme-patient1" / "guidepoints";
  if (!fs::is_directory(p)) ADD_FAILURE() << "real data folder missing: " << p << " (see ../shared/data/README.md)";
  return p;
}

TEST(GpFile, Labels) {
  EXPECT_EQ(gpfile_label("SAX_LV_ENDOCARDIAL"), "lv-endo");
  EXPECT_EQ(gpfile_label("SAX_LV_EPICARDIAL"), "lv-epi");
  EXPECT_EQ(gpfile_label("SAX_RV_FREEWALL"), "rv-freewall");
  EXPECT_EQ(gpfile_label("LAX_LV_EPICARDIAL"), "lax-lv-epi");
}

TEST(GpFile, Patient1EndocardiumAllFrames) {
  const GpFileResult r = read_gpfile(patient_dir());
  const Sequence& seq = r.sequence;
  ASSERT_EQ(seq.frames.size(), 25u);
  EXPECT_EQ(r.slices_used, (std::vector<int>{2, 3, 4, 5, 6}));
  EXPECT_EQ(r.slices.size(), 11u);
  EXPECT_EQ(seq.space, "LPS");
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    SCOPED_TRACE(f);
    EXPECT_DOUBLE_EQ(seq.frames[f].time_ms, static_cast<double>(f));
    ASSERT_GE(seq.frames[f].slices.size(), 1u);
    for (std::size_t k = 0; k < seq.frames[f].slices.size(); ++k) {
      const Slice& s = seq.frames[f].slices[k];
      EXPECT_GE(s.id, 2);
      EXPECT_LE(s.id, 6);
      EXPECT_EQ(s.contours.size(), 1u);
      EXPECT_EQ(s.contours[0].label, "lv-endo");
      if (k > 0) {
        EXPECT_GT(s.offset, seq.frames[f].slices[k - 1].offset);
      }
    }
  }
  // The stack normal is the SliceInfoFile image normal (row x column) up to sign, and the
  // slices are 17.7 mm apart (README).
  const Vec3 n = r.slices[1].normal;
  EXPECT_GT(std::abs(dot(n, seq.normal)), std::cos(0.5 * 3.14159265 / 180));
  const auto& sl = seq.frames[0].slices;
  ASSERT_EQ(sl.size(), 5u);
  for (std::size_t k = 1; k < sl.size(); ++k) EXPECT_NEAR(sl[k].offset - sl[k - 1].offset, 17.7, 0.1);
}

TEST(GpFile, Patient1EpicardiumIsClosedWithTheSeptum) {
  GpFileOptions o;
  o.contour_types = {"SAX_LV_ENDOCARDIAL", "SAX_LV_EPICARDIAL"};
  const GpFileResult r = read_gpfile(patient_dir(), o);
  ASSERT_EQ(r.sequence.frames.size(), 25u);
  std::set<std::string> labs;
  for (const Slice& s : r.sequence.frames[0].slices)
    for (const Contour& c : s.contours) labs.insert(c.label);
  EXPECT_EQ(labs, (std::set<std::string>{"lv-endo", "lv-epi"}));
  const bool noted = std::any_of(r.notes.begin(), r.notes.end(),
                                 [](const std::string& n) { return n.find("SAX_RV_SEPTUM") != std::string::npos; });
  EXPECT_TRUE(noted);
}

TEST(GpFile, LongAxisSlicesAreSkippedWithANote) {
  GpFileOptions o;
  o.contour_types = {"SAX_LV_ENDOCARDIAL", "LAX_LV_ENDOCARDIAL"};
  const GpFileResult r = read_gpfile(fs::path(C4D_CORPUS_DIR) / "gpfile" / "good_two_frames_with_lax", o);
  EXPECT_EQ(r.slices_used, (std::vector<int>{2, 3}));
  EXPECT_EQ(r.slices_skipped, std::vector<int>{7});
  const bool noted = std::any_of(r.notes.begin(), r.notes.end(),
                                 [](const std::string& n) { return n.find("long-axis") != std::string::npos; });
  EXPECT_TRUE(noted);
}

// Every long-axis contour is kept for --align-slices, whatever the chosen types: one curve per frame, view and
// type, in file order (patient 1: 3 views of the LV endocardium per frame, with 69, 66 and 73 points in frame 0, as they come in its file).
TEST(GpFile, Patient1LongAxisContoursAreKeptForAlignment) {
  const GpFileResult r = read_gpfile(patient_dir());
  std::vector<std::size_t> endo0;
  std::set<int> frames;
  for (const GuideCurve& c : r.long_axis) {
    EXPECT_EQ(c.label.rfind("lax-", 0), 0u) << c.label;
    frames.insert(c.frame);
    if (c.frame == 0 && c.label == "lax-lv-endo") endo0.push_back(c.points.size());
  }
  EXPECT_EQ(frames.size(), 25u);
  EXPECT_EQ(endo0, (std::vector<std::size_t>{69, 66, 73}));
}

// The RV endocardium: each slice's free wall and septum arcs joined into one closed contour, whose points are
// the free wall's and (nearly all of) the septum's, on every frame and slice that has both.
TEST(GpFile, Patient1RvFreeWallAndSeptumJoined) {
  GpFileOptions o;
  o.contour_types = {"SAX_RV_FREEWALL", "SAX_RV_SEPTUM"};
  const GpFileResult r = read_gpfile(patient_dir(), o);
  const Sequence& seq = r.sequence;
  ASSERT_EQ(seq.frames.size(), 25u);
  GpFileOptions wall_only;
  wall_only.contour_types = {"SAX_RV_FREEWALL"};
  const Sequence walls = read_gpfile(patient_dir(), wall_only).sequence;
  int joined = 0;
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    for (const Slice& s : seq.frames[f].slices) {
      SCOPED_TRACE(testing::Message() << "frame " << f << " slice " << s.id);
      ASSERT_EQ(s.contours.size(), 1u);
      EXPECT_EQ(s.contours[0].label, "rv-endo");
      for (const Slice& w : walls.frames[f].slices)
        if (w.id == s.id && w.contours[0].points.size() < s.contours[0].points.size()) ++joined;
    }
  EXPECT_GE(joined, 100);  // 115 of the study's contours have both arcs
  EXPECT_TRUE(std::any_of(r.notes.begin(), r.notes.end(),
                          [](const std::string& n) { return n.find("joined into \"rv-endo\"") != std::string::npos; }));
}

TEST(GpFile, MissingSliceInfoNamesFolderAndFile) {
  try {
    read_gpfile(fs::path(C4D_CORPUS_DIR) / "gpfile" / "bad_22_missing_sliceinfo");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(e.code(), ErrorCode::MissingCompanion);
    EXPECT_NE(std::string(e.what()).find("SliceInfoFile.txt"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("bad_22_missing_sliceinfo"), std::string::npos);
  }
}

TEST(GpFile, ErrorsNameTheFrameFileAndLine) {
  const std::string info =
      "a.dcm\tsliceID: "
      "\t2\tImagePositionPatient\t0\t0\t0\tImageOrientationPatient\t1\t0\t0\t0\t1\t0\tPixelSpacing\t1\t1\n";
  const std::string good =
      "x\ty\tz\tcontour type\tsliceID\n0\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n"
      "9\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n0\t9\t0\tSAX_LV_ENDOCARDIAL\t2\n";
  const std::string bad =
      "x\ty\tz\tcontour type\tsliceID\n0\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n"
      "9\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n0\t9\tzz\tSAX_LV_ENDOCARDIAL\t2\n";
  try {
    parse_gpfile_texts({good, bad}, info, "dir");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Parse);
    EXPECT_NE(std::string(e.what()).find("dir/GPFile_001.txt: line 4"), std::string::npos) << e.what();
  }
  const std::string degenerate =
      "x\ty\tz\tcontour type\tsliceID\n0\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n"
      "9\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n";
  GpFileOptions strict;
  strict.repair = false;
  try {
    parse_gpfile_texts({good, degenerate}, info, "dir", strict);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::DegenerateContour);
    EXPECT_NE(std::string(e.what()).find("dir/GPFile_001.txt: line 2, frame 1, slice 2"), std::string::npos)
        << e.what();
  }
}

TEST(GpFile, EveryTruncatedPrefixFailsCleanly) {
  const std::string info =
      "a.dcm\tsliceID: "
      "\t2\tImagePositionPatient\t0\t0\t0\tImageOrientationPatient\t1\t0\t0\t0\t1\t0\tPixelSpacing\t1\t1\n";
  const std::string frame =
      "x\ty\tz\tcontour type\tsliceID\n0\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n"
      "9\t0\t0\tSAX_LV_ENDOCARDIAL\t2\n0\t9\t0\tSAX_LV_ENDOCARDIAL\t2\n";
  for (std::size_t n = 0; n < frame.size(); ++n) {
    try {
      parse_gpfile_texts({frame.substr(0, n)}, info, "dir");
    } catch (const Error&) {}
  }
  for (std::size_t n = 0; n < info.size(); ++n) {
    try {
      parse_gpfile_texts({frame}, info.substr(0, n), "dir");
    } catch (const Error&) {}
  }
  EXPECT_NO_THROW(parse_gpfile_texts({frame}, info, "dir"));
}

//! Every folder in tests/corpus/gpfile: bad_NN_* must fail with ErrorCode NN, good_* read.
// The corpus names the strict errors (--strict); the default repairs some of them (contour_repair_test,
// repair_cli_test), and must still read every good entry and fail every bad one with some c4d::Error or a
// valid result.
TEST(GpFile, Corpus) {
  GpFileOptions strict;
  strict.repair = false;
  const test::CorpusCounts n = test::check_corpus(
      "gpfile", [&](const fs::path& p) { read_gpfile(p, strict); }, /*folders=*/true);
  EXPECT_GE(n.bad, 10);
}

TEST(GpFile, CorpusWithRepairsNeverCrashes) {
  for (const auto& e : fs::directory_iterator(fs::path(C4D_CORPUS_DIR) / "gpfile")) {
    SCOPED_TRACE(e.path().string());
    try {
      read_gpfile(e.path());
    } catch (const Error&) {}
  }
}

}  // namespace
}  // namespace c4d
