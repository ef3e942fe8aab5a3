// Tests of the contour4d JSON reader and writer (include/contour4d/io/contours_json.h).
#include "contour4d/io/contours_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "contour4d/core/errors.h"
#include "corpus_check.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

//! Circle of radius r on the plane through `center` with unit normal n (in-plane axes from make_plane).
std::vector<Vec3> circle(Vec3 center, Vec3 n, double r, int count = 24) {
  const Plane pl = make_plane(center, n);
  std::vector<Vec3> pts;
  for (int k = 0; k < count; ++k) {
    const double a = 2 * std::numbers::pi * k / count;
    pts.push_back(from_plane(pl, {r * std::cos(a), r * std::sin(a)}));
  }
  return pts;
}

//! An oblique stack: 4 slices 8 mm apart, 3 frames, two labels on slice 2.
Sequence oblique_stack() {
  const Vec3 n = normalized(Vec3{0.3, -0.5, 0.8});
  const Vec3 o{-40.25, 12.5, 101.0};
  std::vector<RawContour> raw;
  for (int f = 0; f < 3; ++f) {
    int index = 0;
    for (int s = 0; s < 4; ++s) {
      RawContour rc;
      rc.frame = f;
      rc.index = index++;
      rc.contour = {"lv-endo", s + 1, circle(o + (8.0 * s) * n, n, 20.0 - s - f)};
      raw.push_back(rc);
      if (s == 2) {
        rc.index = index++;
        rc.contour = {"lv-epi", s + 1, circle(o + (8.0 * s) * n, n, 26.0 - s)};
        raw.push_back(rc);
      }
    }
  }
  return build_sequence(raw, 3, {0.0, 33.5, 67.0}, "memory");
}

ErrorCode code_of(const std::string& text, std::string* message = nullptr) {
  try {
    parse_contours_json(text, "test.json");
  } catch (const Error& e) {
    if (message) *message = e.what();
    return e.code();
  }
  return static_cast<ErrorCode>(0);
}

TEST(ContoursJson, RoundTripIsByteIdentical) {
  const Sequence seq = oblique_stack();
  const std::string a = format_contours_json(seq);
  const Sequence back = parse_contours_json(a, "a.json");
  EXPECT_EQ(format_contours_json(back), a);
  ASSERT_EQ(back.frames.size(), seq.frames.size());
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    EXPECT_DOUBLE_EQ(back.frames[f].time_ms, seq.frames[f].time_ms);
    ASSERT_EQ(back.frames[f].slices.size(), seq.frames[f].slices.size());
    for (std::size_t s = 0; s < seq.frames[f].slices.size(); ++s) {
      const Slice& x = seq.frames[f].slices[s];
      const Slice& y = back.frames[f].slices[s];
      EXPECT_EQ(x.id, y.id);
      EXPECT_NEAR(x.offset, y.offset, 1e-5);
      ASSERT_EQ(x.contours.size(), y.contours.size());
      for (std::size_t c = 0; c < x.contours.size(); ++c) {
        EXPECT_EQ(x.contours[c].label, y.contours[c].label);
        ASSERT_EQ(x.contours[c].points.size(), y.contours[c].points.size());
        for (std::size_t i = 0; i < x.contours[c].points.size(); ++i)
          EXPECT_LT(distance(x.contours[c].points[i], y.contours[c].points[i]), 1e-6);
      }
    }
  }
  EXPECT_LT(distance(back.normal, seq.normal), 1e-9);
  EXPECT_EQ(back.space, "LPS");
}

TEST(ContoursJson, MinimalFileWithDefaults) {
  const std::string text = R"({"format": "contour4d-contours", "version": 1,
    "frames": [{"contours": [{"slice": 4, "points": [[0,0,5],[10,0,5],[10,10,5],[0,10,5],[0,0,5]]}]},
               {"contours": [{"slice": 4, "points": [[0,0,5],[0,9,5],[9,9,5],[9,0,5]]}]}]})";
  const Sequence seq = parse_contours_json(text, "min.json");
  ASSERT_EQ(seq.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(seq.frames[1].time_ms, 1.0);  // index × 1 ms when absent
  EXPECT_EQ(seq.space, "LPS");
  EXPECT_EQ(seq.units, "mm");
  const Contour& c = seq.frames[0].slices[0].contours[0];
  EXPECT_EQ(c.points.size(), 4u);  // repeated first point dropped
  EXPECT_EQ(c.label, "");
  EXPECT_EQ(c.slice, 4);
  EXPECT_NEAR(std::abs(seq.normal.z), 1.0, 1e-12);
  EXPECT_NEAR(seq.frames[0].slices[0].offset * seq.normal.z, 5.0, 1e-12);
}

TEST(ContoursJson, SpaceIsRead) {
  const std::string text = R"({"format": "contour4d-contours", "version": 1, "space": "RAS",
    "frames": [{"contours": [{"slice": 0, "points": [[0,0,0],[1,0,0],[0,1,0]]}]}]})";
  EXPECT_EQ(parse_contours_json(text, "x").space, "RAS");
  EXPECT_NE(format_contours_json(parse_contours_json(text, "x")).find("\"RAS\""), std::string::npos);
}

TEST(ContoursJson, SyntaxErrorReportsLine) {
  const std::string text = "{\"format\": \"contour4d-contours\",\n\"version\": 1,\n\"frames\": [ }\n";
  std::string msg;
  EXPECT_EQ(code_of(text, &msg), ErrorCode::Parse);
  EXPECT_NE(msg.find("test.json: line 3"), std::string::npos) << msg;
}

TEST(ContoursJson, ContourErrorsNameLineFrameAndContour) {
  const std::string text = std::string(R"({"format": "contour4d-contours", "version": 1, "frames": [
  {"contours": [
    {"slice": 0, "points": [[0,0,0],[10,0,0],[0,10,0]]}
  ]},
  {"contours": [
    {"slice": 0, "points": [[0,0,0],[10,0,0],[0,10,0]]},
    {"slice": 1, "points": [[0,0,9],[10,0,9]]}
  ]}]})");
  std::string msg;
  EXPECT_EQ(code_of(text, &msg), ErrorCode::DegenerateContour);
  EXPECT_NE(msg.find("test.json: line 7, frame 1, slice 1, contour 1"), std::string::npos) << msg;
}

TEST(ContoursJson, OverflowIsNonFiniteWithLine) {
  const std::string text =
      "{\"format\": \"contour4d-contours\", \"version\": 1, \"frames\": [\n"
      "{\"contours\": [{\"slice\": 0, \"points\": [[0,0,0],[1e999,0,0],[0,1,0]]}]}]}";
  std::string msg;
  EXPECT_EQ(code_of(text, &msg), ErrorCode::NonFinite);
  EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
}

TEST(ContoursJson, DeepNestingIsRejectedCleanly) {
  const std::string text = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_EQ(code_of(text), ErrorCode::Parse);
}

TEST(ContoursJson, EveryTruncatedPrefixFailsCleanly) {
  // STYLE.md rule 11: each prefix in a fresh allocation gives a clean c4d::Error, never a crash.
  const std::string full = format_contours_json(oblique_stack());
  ASSERT_NO_THROW(parse_contours_json(full, "full.json"));
  std::size_t step = std::max<std::size_t>(1, full.size() / 2000);
  for (std::size_t n = 0; n + 1 < full.size(); n += (n < 400 ? 1 : step)) {
    const std::string prefix(full.data(), n);
    const ErrorCode c = code_of(prefix);
    // Trailing whitespace aside, every proper prefix is incomplete JSON.
    if (full.find_first_not_of(" \n", n) == std::string::npos) continue;
    EXPECT_TRUE(c == ErrorCode::Parse || c == ErrorCode::EmptyFile)
        << "prefix of " << n << " bytes gave " << static_cast<int>(c);
  }
}

TEST(ContoursJson, ReadFileErrors) {
  try {
    read_contours_json("/nonexistent/contours.json");
    FAIL() << "no exception";
  } catch (const IoError& e) {
    EXPECT_EQ(e.code(), ErrorCode::FileNotFound);
  }
}

//! Every file in tests/corpus/contours_json: bad_NN_*.json must fail with ErrorCode NN, good_* parse.
TEST(ContoursJson, Corpus) {
  const test::CorpusCounts n = test::check_corpus("contours_json", [](const fs::path& p) { read_contours_json(p); });
  EXPECT_GE(n.bad, 15);
  EXPECT_GE(n.good, 2);
}

}  // namespace
}  // namespace c4d
