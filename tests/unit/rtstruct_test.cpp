// DICOM RT structure sets (include/contour4d/io/rtstruct.h): files written by an independent writer
// (tests/python/make_rtstruct.py, pydicom) read back point for point, ROIs as labels, every bad-file class
// with its exit code (in-process and through the CLI), the corpus, every truncated prefix, and the
// reconstruction of each ROI through `contour4d reconstruct --label all`.
#include "contour4d/io/rtstruct.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>

#include "contour4d/core/errors.h"
#include "contour4d/pipeline/input.h"
#include "corpus_check.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const fs::path kCorpus = fs::path(C4D_CORPUS_DIR) / "rtstruct";

struct Shell {
  int code = -1;
  std::string out;
};

Shell sh(const std::string& cmd) {
  Shell r;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((cmd + " 2>&1").c_str(), "r"), pclose);
  std::array<char, 4096> buf{};
  while (pipe && fgets(buf.data(), buf.size(), pipe.get())) r.out += buf.data();
  const int status = pclose(pipe.release());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

Shell cli(const std::string& args) { return sh(std::string(C4D_CLI) + " " + args); }

// A folder of this process's own, removed at exit.
struct TempDir {
  fs::path path = fs::temp_directory_path() / ("c4d_rtstruct_test_" + std::to_string(getpid()));
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// The round-trip files, written once per test process: OUT/rtstruct.dcm and OUT/truth.json.
const fs::path& roundtrip_dir() {
  static const TempDir dir;
  static const bool written = [] {
    const Shell r =
        sh(std::string(C4D_PYTHON) + " " + C4D_TEST_SCRIPTS + "/make_rtstruct.py roundtrip " + dir.path.string());
    EXPECT_EQ(r.code, 0) << "make_rtstruct.py (needs python3-pydicom): " << r.out;
    return r.code == 0;
  }();
  (void)written;
  return dir.path;
}

Json truth() {
  std::ifstream in(roundtrip_dir() / "truth.json");
  return Json::parse(in);
}

template <typename F>
Error error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error thrown";
  return Error(ErrorCode::Internal, {}, "none");
}

// The largest distance (mm) between a true contour and the contour read back with its label, point for point;
// infinity when a true contour has no counterpart. `found` counts the contours matched.
double max_error(const Sequence& seq, const Json& t, std::size_t& found) {
  double worst = 0;
  found = 0;
  for (const Json& tc : t["contours"]) {
    double best = std::numeric_limits<double>::infinity();
    for (const Frame& f : seq.frames)
      for (const Slice& s : f.slices)
        for (const Contour& c : s.contours) {
          if (c.label != tc["label"].get<std::string>() || c.points.size() != tc["points"].size()) continue;
          double d = 0;
          for (std::size_t i = 0; i < c.points.size(); ++i) {
            const Json& p = tc["points"][i];
            d = std::max(d, distance(c.points[i], Vec3{p[0].get<double>(), p[1].get<double>(), p[2].get<double>()}));
          }
          best = std::min(best, d);
        }
    if (std::isfinite(best)) ++found;
    worst = std::max(worst, best);
  }
  return worst;
}

std::size_t contour_count(const Sequence& seq) {
  std::size_t n = 0;
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) n += s.contours.size();
  return n;
}

bool has_note(const InputResult& r, const std::string& part) {
  return std::any_of(r.notes.begin(), r.notes.end(), [&](const std::string& n) { return n.find(part) != n.npos; });
}

TEST(RtStruct, RoiLabelsAreFolderSafe) {
  EXPECT_EQ(roi_label("Lung L", 3), "lung-l");
  EXPECT_EQ(roi_label("PTV_70 Gy", 1), "ptv-70-gy");
  EXPECT_EQ(roi_label("  (Heart)  ", 1), "heart");
  EXPECT_EQ(roi_label("../..", 7), "roi-7");
  EXPECT_EQ(roi_label("", 2), "roi-2");
  EXPECT_EQ(roi_label("Herz \xc3\xa4u\xc3\x9f"
                      "er",
                      4),
            "herz-u-er");                   // UTF-8 bytes separate, never kept
  EXPECT_EQ(roi_label("ALL", 5), "all-5");  // "all" asks for every structure
}

TEST(RtStruct, RoundTripWithinAMicronOnObliquePlanes) {
  const Json t = truth();
  const InputResult r = read_rtstruct(roundtrip_dir() / "rtstruct.dcm");
  EXPECT_EQ(r.format, "dicom-rtstruct");
  EXPECT_EQ(r.sequence.space, "LPS");
  ASSERT_EQ(r.sequence.frames.size(), 1u);  // one 3D time point
  EXPECT_TRUE(r.repairs.empty());
  std::size_t found = 0;
  const double err = max_error(r.sequence, t, found);
  EXPECT_EQ(found, t["contours"].size());
  EXPECT_EQ(contour_count(r.sequence), t["contours"].size());
  EXPECT_LT(err, 1e-3);
  RecordProperty("max_error_mm", std::to_string(err));
  std::printf("RT structure set round trip: %zu contours, max error %.3g mm\n", found, err);
  // The stack normal is the planes' (tilted 20 degrees off z), up to sign.
  const Vec3 n{t["normal"][0].get<double>(), t["normal"][1].get<double>(), t["normal"][2].get<double>()};
  EXPECT_NEAR(std::abs(dot(r.sequence.normal, n)), 1.0, 1e-9);
  // Both ROIs share the planes: the inner ellipsoid's slices are slices of the outer one.
  EXPECT_EQ(r.sequence.frames[0].slices.size(), 19u);
}

TEST(RtStruct, EmptyAndPointRoisAreLeftOutWithANote) {
  const InputResult r = read_rtstruct(roundtrip_dir() / "rtstruct.dcm");
  EXPECT_EQ(labels(r.sequence), (std::vector<std::string>{"inner-ellipsoid", "outer-ellipsoid"}));
  EXPECT_TRUE(has_note(r, "ROI 3 \"Not Drawn\" (not-drawn): no contours, left out"));
  EXPECT_TRUE(has_note(r, "ROI 4 \"Marker\" (marker): no closed planar contour (1 POINT), left out"));
  EXPECT_TRUE(has_note(r, "one frame"));
  EXPECT_TRUE(has_note(r, "EXTERNAL"));  // RTROIInterpretedType
}

TEST(RtStruct, LabelNameOrNumberPicksOneRoi) {
  for (const std::string pick : {"inner-ellipsoid", "inner ellipsoid", "2"}) {
    RtStructOptions o;
    o.label = pick;
    const InputResult r = read_rtstruct(roundtrip_dir() / "rtstruct.dcm", o);
    EXPECT_EQ(labels(r.sequence), std::vector<std::string>{"inner-ellipsoid"}) << pick;
    EXPECT_EQ(contour_count(r.sequence), 9u) << pick;
  }
  RtStructOptions o;
  o.label = "liver";
  const Error e = error_of([&] { read_rtstruct(roundtrip_dir() / "rtstruct.dcm", o); });
  EXPECT_EQ(e.code(), ErrorCode::UnknownLabel);
  EXPECT_NE(std::string(e.what()).find("\"outer-ellipsoid\" (ROI 1 \"Outer Ellipsoid\")"), std::string::npos)
      << e.what();
}

TEST(RtStruct, AskingForAnEmptyRoiIsItsOwnError) {
  for (const std::string pick : {"not-drawn", "Marker"}) {
    RtStructOptions o;
    o.label = pick;
    const Error e = error_of([&] { read_rtstruct(roundtrip_dir() / "rtstruct.dcm", o); });
    EXPECT_EQ(e.code(), ErrorCode::EmptyStructure) << e.what();
    EXPECT_NE(e.where().part.find("ROI"), std::string::npos) << e.what();
  }
}

TEST(RtStruct, RasNegatesXAndY) {
  RtStructOptions lps, ras;
  lps.label = ras.label = "outer-ellipsoid";
  ras.space = "RAS";
  const Sequence a = read_rtstruct(roundtrip_dir() / "rtstruct.dcm", lps).sequence;
  const Sequence b = read_rtstruct(roundtrip_dir() / "rtstruct.dcm", ras).sequence;
  EXPECT_EQ(b.space, "RAS");
  const Vec3 p = a.frames[0].slices[3].contours[0].points[5];
  const Vec3 q = b.frames[0].slices[3].contours[0].points[5];
  EXPECT_DOUBLE_EQ(q.x, -p.x);
  EXPECT_DOUBLE_EQ(q.y, -p.y);
  EXPECT_DOUBLE_EQ(q.z, p.z);
}

TEST(RtStruct, DicomKindSaysWhatAFileIs) {
  const DicomKind ct = dicom_kind(kCorpus / "bad_13_ct_image.dcm");
  EXPECT_FALSE(ct.rtstruct);
  EXPECT_EQ(ct.modality, "CT");
  EXPECT_EQ(ct.sop_class, "CT Image Storage");
  const DicomKind rs = dicom_kind(kCorpus / "good_one_roi_axial.dcm");
  EXPECT_TRUE(rs.rtstruct);
  EXPECT_EQ(rs.sop_class, "RT Structure Set Storage");
  EXPECT_TRUE(is_dicom_file(kCorpus / "good_one_roi_axial.dcm"));
  EXPECT_FALSE(is_dicom_file(kCorpus / "bad_12_not_dicom.dcm"));
}

// The four bad-file classes of issue 44, each with its exit code and a message naming file and place.
TEST(RtStruct, EachBadClassHasItsExitCodeAndSaysWhere) {
  struct Case {
    const char* file;
    ErrorCode code;
    const char* says;
  };
  const Case cases[] = {
      {"bad_27_no_referenced_frame_of_reference.dcm", ErrorCode::MissingGeometry,
       "no ReferencedFrameOfReferenceSequence (3006,0010)"},
      {"bad_27_roi_frame_of_reference_not_referenced.dcm", ErrorCode::MissingGeometry,
       "ROI 1 \"GTV\": frame of reference"},
      {"bad_28_empty_roi.dcm", ErrorCode::EmptyStructure, "ROI 1 \"GTV\": no contours"},
      {"bad_28_only_point_contours.dcm", ErrorCode::EmptyStructure, "no closed planar contour (1 POINT)"},
      {"bad_13_ct_image.dcm", ErrorCode::Format, "a CT image (CT Image Storage, Modality CT), not an RT structure set"},
      {"bad_13_rt_plan.dcm", ErrorCode::Format, "Modality RTPLAN), not an RT structure set"},
      {"bad_12_truncated_in_contour_data.dcm", ErrorCode::Parse, "not readable as DICOM"},
      {"bad_13_contour_data_not_triplets.dcm", ErrorCode::Format, "ROI 1 \"GTV\", contour 0: ContourData holds 29"},
  };
  for (const Case& c : cases) {
    const Error e = error_of([&] { read_rtstruct(kCorpus / c.file); });
    EXPECT_EQ(e.code(), c.code) << c.file << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(c.file), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
  }
}

TEST(RtStruct, Corpus) {
  const test::CorpusCounts n = test::check_corpus("rtstruct", [](const fs::path& p) { read_rtstruct(p); });
  EXPECT_GE(n.good, 4);
  EXPECT_GE(n.bad, 20);
}

// Every prefix of a valid file ends in a c4d::Error or a structure set read: never a crash or another exception.
TEST(RtStruct, EveryTruncatedPrefixFailsCleanly) {
  std::ifstream in(kCorpus / "good_one_roi_axial.dcm", std::ios::binary);
  const std::string whole{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GT(whole.size(), 1000u);
  const fs::path f = fs::temp_directory_path() / ("c4d_rtstruct_prefix_" + std::to_string(getpid()) + ".dcm");
  int failed = 0;
  for (std::size_t n = 0; n < whole.size(); n += 7) {
    std::ofstream(f, std::ios::binary).write(whole.data(), static_cast<std::streamsize>(n));
    try {
      read_rtstruct(f);
    } catch (const Error&) {
      ++failed;
    }
  }
  fs::remove(f);
  EXPECT_GT(failed, static_cast<int>(whole.size() / 7 * 9 / 10));
}

TEST(RtStruct, CliExitCodesAndMessages) {
  const fs::path out = roundtrip_dir() / "bad.json";
  for (const auto& [file, code] :
       std::vector<std::pair<std::string, int>>{{"bad_27_no_referenced_frame_of_reference.dcm", 27},
                                                {"bad_28_empty_roi.dcm", 28},
                                                {"bad_13_ct_image.dcm", 13},
                                                {"bad_12_truncated_in_contour_data.dcm", 12},
                                                {"bad_11_empty.dcm", 11}}) {
    const Shell r = cli("extract " + (kCorpus / file).string() + " -o " + out.string());
    EXPECT_EQ(r.code, code) << file << ": " << r.out;
    EXPECT_NE(r.out.find(file), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out));
  }
}

// The ctest of issue 44: written by pydicom, read back by `contour4d extract` (contour JSON), compared with
// the truth by the writer's side (make_rtstruct.py check) within 0.001 mm.
TEST(RtStruct, ExtractRoundTripCheckedByTheWriter) {
  const fs::path d = roundtrip_dir();
  const Shell e = cli("extract " + (d / "rtstruct.dcm").string() + " -o " + (d / "read.json").string());
  ASSERT_EQ(e.code, 0) << e.out;
  EXPECT_NE(e.out.find("dicom-rtstruct"), std::string::npos) << e.out;
  const Shell c = sh(std::string(C4D_PYTHON) + " " + C4D_TEST_SCRIPTS + "/make_rtstruct.py check " +
                     (d / "read.json").string() + " " + (d / "truth.json").string());
  EXPECT_EQ(c.code, 0) << c.out;
  const Json j = Json::parse(c.out);
  EXPECT_LT(j["max_error_mm"].get<double>(), 1e-3);
  EXPECT_EQ(j["unmatched"].get<int>(), 0);
  std::printf("extract -> make_rtstruct.py check: %s", c.out.c_str());
}

TEST(RtStruct, FolderDispatch) {
  const fs::path d = roundtrip_dir() / "folder";
  fs::create_directories(d);
  fs::copy_file(kCorpus / "bad_13_ct_image.dcm", d / "CT.1.dcm", fs::copy_options::overwrite_existing);
  try {
    read_contours(d);
    ADD_FAILURE() << "a folder of CT images alone was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Format);
    EXPECT_NE(std::string(e.what()).find("RT structure set"), std::string::npos) << e.what();
  }
  fs::copy_file(roundtrip_dir() / "rtstruct.dcm", d / "RS.1", fs::copy_options::overwrite_existing);  // no extension
  InputOptions o;
  o.label = "Outer Ellipsoid";
  const InputResult r = read_contours(d, o);
  EXPECT_EQ(r.format, "dicom-rtstruct");
  EXPECT_EQ(labels(r.sequence), std::vector<std::string>{"outer-ellipsoid"});
  EXPECT_EQ(r.timing, "single frame");
}

TEST(RtStruct, ReconstructEveryRoi) {
  if (!C4D_HEAVY_TESTS) GTEST_SKIP() << "C4D_HEAVY_TESTS is off";
  const fs::path d = roundtrip_dir();
  const Shell r =
      cli("reconstruct " + (d / "rtstruct.dcm").string() + " --label all --threads 2 -o " + (d / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const Json t = truth();
  std::ifstream in(d / "out" / "report.json");
  const Json report = Json::parse(in);
  for (const std::string name : {"outer-ellipsoid", "inner-ellipsoid"}) {
    EXPECT_TRUE(fs::exists(d / "out" / name / "mesh.pvd")) << name;
    std::ifstream sin(d / "out" / name / "report.json");
    const Json s = Json::parse(sin);
    const double v = s["summary"]["volume_ml"][0].get<double>() * 1000.0;
    const double truth_v = t["volume_mm3"][name].get<double>();
    std::printf("%s: volume %.0f mm3, ellipsoid %.0f mm3 (%+.1f %%)\n", name.c_str(), v, truth_v,
                100.0 * (v / truth_v - 1.0));
    EXPECT_NEAR(v / truth_v, 1.0, 0.05) << name;
  }
}

}  // namespace
}  // namespace c4d
