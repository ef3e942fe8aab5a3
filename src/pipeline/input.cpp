// One entry point for every contour input: the reader is chosen from what the path is.
#include "contour4d/pipeline/input.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "contour4d/core/contour_gaps.h"
#include "contour4d/core/errors.h"
#include "contour4d/io/contours_json.h"
#include "contour4d/io/gpfile.h"
#include "contour4d/io/images.h"
#include "contour4d/io/rtstruct.h"
#include "contour4d/io/sunnybrook.h"
#include "contour4d/extract/mask_contours.h"

namespace c4d {

namespace {

namespace fs = std::filesystem;

constexpr const char* kSupported =
    "supported inputs: a contour4d JSON file (*.json, see docs/formats.md); a biv-me GPFile folder "
    "(GPFile_000.txt ... plus SliceInfoFile.txt) or its parent holding a \"guidepoints\" folder; a Sunnybrook-style "
    "patient folder (i-contours/, o-contours/, DICOM images); a DICOM RT structure set (RTSTRUCT: a .dcm file, or "
    "a folder holding one); label images (.nii, .nii.gz, .nrrd, .mha, .mhd: one 4D "
    "file, one file per frame, a folder of them or a pattern like 'patient001_frame*_gt.nii.gz')";

bool has_gpfiles(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return false;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("GPFile_", 0) == 0 && n.size() > 11 && n.compare(n.size() - 4, 4, ".txt") == 0) return true;
  }
  return false;
}

// Whether a folder holds DICOM files (the "DICM" mark at byte 128), looking at its first files only.
bool has_dicom_files(const fs::path& dir) {
  std::error_code ec;
  int looked = 0;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec)) continue;
    if (++looked > 64) break;
    std::ifstream in(e.path(), std::ios::binary);
    char head[132] = {};
    if (in.read(head, sizeof head) && std::string_view(head + 128, 4) == "DICM") return true;
  }
  return false;
}

std::string lower_extension(const fs::path& p) {
  std::string e = p.extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

bool is_dicom_input(const fs::path& file) { return lower_extension(file) == ".dcm" || is_dicom_file(file); }

// The RT structure sets among a folder's DICOM files (headers only: pixel data stays on disk).
std::vector<fs::path> rtstruct_files(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec) || !is_dicom_input(e.path())) continue;
    try {
      if (dicom_kind(e.path()).rtstruct) out.push_back(e.path());
    } catch (const Error&) {
      // an unreadable file beside the images is not the structure set
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// An RT structure set: the ROI (--label) is chosen on reading, by its label, name or number.
InputResult read_rtstruct_input(const fs::path& file, const InputOptions& options, const std::string& space) {
  if (!options.contour_types.empty())
    throw InvalidInput(ErrorCode::Usage, Location{file.string()}, "contour types (--type) apply to GPFile folders only",
                       "use --label to choose an ROI of an RT structure set");
  RtStructOptions ro;
  ro.label = options.label;
  ro.space = space;
  ro.stack = options.stack;
  ro.repair = !options.strict;
  return read_rtstruct(file, ro);
}

// A folder of DICOM files: the one RT structure set among them, else what is wrong.
fs::path rtstruct_in_folder(const fs::path& dir, const Location& where) {
  const std::vector<fs::path> found = rtstruct_files(dir);
  if (found.size() == 1) return found.front();
  if (found.size() > 1)
    throw IoError(ErrorCode::Format, where,
                  fmt::format("folder holds {} RT structure sets ({}, {}, ...)", found.size(),
                              found[0].filename().string(), found[1].filename().string()),
                  "give the one to read");
  throw IoError(ErrorCode::Format, where,
                "folder holds DICOM images but no contours: contour4d reads contours drawn on them (an RT structure "
                "set, a Sunnybrook-style folder with i-contours/ and o-contours/ beside the images) or label images, "
                "not the images alone",
                kSupported);
}

}  // namespace

namespace {

// The GPFile contour types a label asks for when --type is not given: "all" every short-axis structure (the RV
// endocardium as its free wall and septum, joined on reading), else the types of that label; none: the reader's
// default (SAX_LV_ENDOCARDIAL).
std::vector<std::string> gpfile_types_for(const std::string& label) {
  static const std::map<std::string, std::vector<std::string>> kTypes = {
      {"all", {"SAX_LV_ENDOCARDIAL", "SAX_LV_EPICARDIAL", "SAX_RV_FREEWALL", "SAX_RV_SEPTUM"}},
      {"lv-endo", {"SAX_LV_ENDOCARDIAL"}},
      {"lv-epi", {"SAX_LV_EPICARDIAL"}},
      {"lv-wall", {"SAX_LV_ENDOCARDIAL", "SAX_LV_EPICARDIAL"}},
      {"rv-endo", {"SAX_RV_FREEWALL", "SAX_RV_SEPTUM"}}};
  const auto it = kTypes.find(label);
  return it == kTypes.end() ? std::vector<std::string>{} : it->second;
}

// The pixel size of the slices a GPFile folder's contours were traced on (mean over the slices used; 0: none).
double mean_pixel_mm(const GpFileResult& r) {
  double sum = 0.0;
  int count = 0;
  for (const GpFileSlice& s : r.slices)
    if (s.used && s.pixel_mm > 0.0) {
      sum += s.pixel_mm;
      ++count;
    }
  return count > 0 ? sum / count : 0.0;
}

InputResult read_any(const fs::path& input, const InputOptions& options) {
  Location where;
  where.file = input.string();
  std::error_code ec;
  const std::string name = input.filename().string();
  const bool pattern = name.find_first_of("*?") != std::string::npos;
  if (!pattern && !fs::exists(input, ec))
    throw IoError(ErrorCode::FileNotFound, where, "no such file or folder", kSupported);

  InputResult result;
  const std::string space = options.space == "ras" || options.space == "RAS" ? "RAS" : "LPS";
  if (fs::is_directory(input, ec) && is_sunnybrook_folder(input)) {
    SunnybrookOptions so;
    so.space = space;
    so.contours = options.label == "lv-epi" ? SunnybrookContours::Epicardium
                  : options.label == "all"  ? SunnybrookContours::Both
                                            : SunnybrookContours::Endocardium;
    so.stack = options.stack;
    result = read_sunnybrook(input, so);
  } else if (is_label_image_input(input)) {
    MaskExtractOptions mo;
    if (!options.label.empty() && options.label != "all") mo.labels = {options.label};
    mo.preset = options.label_preset;
    mo.slice_axis = options.slice_axis;
    mo.space = space;
    mo.stack = options.stack;
    result = read_label_image_contours(input, mo);
    return result;  // the label was applied during extraction
  } else if (fs::is_directory(input, ec)) {
    fs::path dir = input;
    if (!has_gpfiles(dir) && has_gpfiles(dir / "guidepoints")) dir = dir / "guidepoints";
    if (!has_gpfiles(dir) && has_dicom_files(input))
      return read_rtstruct_input(rtstruct_in_folder(input, where), options, space);  // the label chosen on reading
    if (!has_gpfiles(dir)) throw IoError(ErrorCode::Format, where, "folder holds no GPFile_*.txt files", kSupported);
    GpFileOptions gp;
    gp.contour_types = options.contour_types.empty() ? gpfile_types_for(options.label) : options.contour_types;
    gp.stack = options.stack;
    gp.repair = !options.strict;
    GpFileResult r = read_gpfile(dir, gp);
    result.sequence = std::move(r.sequence);
    result.repairs = std::move(r.repairs);
    result.format = "gpfile";
    result.notes = std::move(r.notes);
    result.pixel_mm = mean_pixel_mm(r);
    result.long_axis = std::move(r.long_axis);
  } else if (fs::is_regular_file(input, ec) && is_dicom_input(input)) {
    return read_rtstruct_input(input, options, space);  // the label was chosen on reading
  } else if (lower_extension(input) == ".json") {
    if (!options.contour_types.empty())
      throw InvalidInput(ErrorCode::Usage, where, "contour types (--type) apply to GPFile folders only",
                         "use --label to choose contours of a JSON file");
    result.sequence = read_contours_json(input, options.stack, options.strict ? nullptr : &result.repairs);
    result.format = "contour4d-json";
  } else {
    throw IoError(ErrorCode::Format, where, "unrecognised input (extension \"" + input.extension().string() + "\")",
                  kSupported);
  }
  if (!options.label.empty() && options.label != "all") {
    result.sequence = select_label(result.sequence, options.label);
    result.notes.push_back("label: only \"" + options.label + "\" kept");
  }
  return result;
}

// The readers that find no time in their data number the frames 0, 1, 2, ... ms (GPFile, label images, a
// Sunnybrook folder without TriggerTime): a sequence timed exactly so carries no time of its own.
bool has_own_times(const Sequence& seq) {
  if (seq.frames.size() < 2) return true;
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    if (seq.frames[f].time_ms != static_cast<double>(f)) return true;
  return false;
}

// Frame times: the data's where it has them, else --frame-ms or --cycle-ms, else unknown (said so).
void apply_frame_times(InputResult& r, const InputOptions& o) {
  std::vector<Frame>& frames = r.sequence.frames;
  const std::size_t n = frames.size();
  const bool asked = o.frame_ms > 0 || o.cycle_ms > 0;
  if (n < 2) {
    r.timing = "single frame";
    return;
  }
  if (has_own_times(r.sequence)) {
    r.timing = "data";
    if (asked) r.notes.push_back("frame times from the data; --frame-ms/--cycle-ms ignored");
    return;
  }
  if (!asked) {
    r.timing = "unknown";
    r.notes.push_back(
        "frame times: unknown in this input (frames numbered 0, 1, 2, ... ms); give --frame-ms or --cycle-ms");
    return;
  }
  const double step = o.frame_ms > 0 ? o.frame_ms : o.cycle_ms / static_cast<double>(n);
  for (std::size_t f = 0; f < n; ++f) frames[f].time_ms = static_cast<double>(f) * step;
  r.timing = o.frame_ms > 0 ? "--frame-ms" : "--cycle-ms";
  r.notes.push_back(fmt::format("frame times: {:g} ms apart ({})", step, r.timing));
}

// The share of the tolerance the smoothing spline may use: the rest is left to the mesh (its chords, the
// frames' fit), so that the surface stays within the tolerance of every traced point.
constexpr double kSplineShare = 0.9;

// Traced contours smoothed within their tolerance (contour_smoothing.h): half a pixel of the images they were
// traced on unless the user gives one; inputs without pixels (exact or fitted contours) are left as they are.
void smooth_traced_contours(InputResult& r, const InputOptions& o) {
  if (o.contour_tolerance_mm >= 0.0) {
    r.smoothing_tolerance_mm = o.contour_tolerance_mm;
    r.smoothing_source = o.contour_tolerance_mm > 0.0 ? "--contour-tolerance" : "--exact-contours";
  } else if (r.pixel_mm > 0.0) {
    r.smoothing_tolerance_mm = 0.5 * r.pixel_mm;
    r.smoothing_source =
        fmt::format("half the pixel size of the images the contours were traced on ({:.4g} mm)", r.pixel_mm);
  } else {
    r.smoothing_source = "exact contours (no pixel size in this input)";
  }
  if (!(r.smoothing_tolerance_mm > 0.0)) return;
  r.smoothing = smooth_contours(r.sequence, kSplineShare * r.smoothing_tolerance_mm);
  double worst = 0.0;
  for (const ContourSmoothing& c : r.smoothing) worst = std::max(worst, c.moved_max_mm);
  r.notes.push_back(fmt::format(
      "contours smoothed within {:.3g} mm ({}); moved at most {:.3g} mm; --exact-contours keeps them as traced",
      r.smoothing_tolerance_mm, r.smoothing_source, worst));
}

// Breath-hold shifts undone on request (slice_alignment.h), said in the notes: onto the long-axis contours where
// the input has them, else onto the centroids' axis.
void align_slices_on_request(InputResult& r, const InputOptions& o) {
  if (!o.align_slices) return;
  r.aligned = true;
  r.alignment = align_slices_to_curves(r.sequence, r.long_axis);
  if (r.alignment.degree < 0) {
    r.notes.push_back("--align-slices: fewer than four slices hold " + r.alignment.label + "; nothing moved");
    return;
  }
  const auto worst = std::max_element(r.alignment.shifts.begin(), r.alignment.shifts.end(),
                                      [](const SliceShift& a, const SliceShift& b) { return a.shift_mm < b.shift_mm; });
  if (r.alignment.method == "long-axis") {
    int crossings = 0, still = 0;
    for (const SliceShift& s : r.alignment.shifts) {
      crossings += s.crossings;
      still += s.weight == 0.0;
    }
    r.notes.push_back(
        fmt::format("slices aligned in plane onto the long-axis contours that cross them ({}: {} "
                    "crossings): {} slices, moved at most {:.2f} mm (slice {}){}; see report.json "
                    "\"slice_alignment\"",
                    r.alignment.label, crossings, r.alignment.shifts.size(), worst->shift_mm, worst->slice,
                    still ? fmt::format(", {} left in place (too few crossings, or from one view only)", still) : ""));
    return;
  }
  r.notes.push_back(
      fmt::format("slices aligned in plane on the {} centroids' axis (degree {}): {} slices, moved at "
                  "most {:.2f} mm (slice {}); see report.json \"slice_alignment\"",
                  r.alignment.label, r.alignment.degree, r.alignment.shifts.size(), worst->shift_mm, worst->slice));
}

// Slices contoured in some frames only, listed and said: those frames are reconstructed from what they have.
void note_partial_slices(InputResult& r) {
  const std::vector<Frame>& frames = r.sequence.frames;
  std::map<int, std::vector<bool>> present;
  for (std::size_t f = 0; f < frames.size(); ++f)
    for (const Slice& s : frames[f].slices) {
      std::vector<bool>& p = present[s.id];
      p.resize(frames.size(), false);
      p[f] = true;
    }
  for (const auto& [id, p] : present) {
    SliceGap gap{id, {}};
    for (std::size_t f = 0; f < p.size(); ++f)
      if (!p[f]) gap.missing_frames.push_back(static_cast<int>(f));
    if (gap.missing_frames.empty()) continue;
    r.notes.push_back(
        fmt::format("slice {} has no contours in {} of {} frames ({}): those frames are reconstructed "
                    "from the slices they have",
                    id, gap.missing_frames.size(), frames.size(), fmt::join(gap.missing_frames, ", ")));
    r.slices_in_some_frames.push_back(std::move(gap));
  }
}

// Contours left out of some frames, filled in time where the slice has them in other frames (contour_gaps.h),
// each listed as a repair; --strict leaves them out.
void fill_gaps_in_time(InputResult& r, const InputOptions& o) {
  if (o.strict) return;
  for (const ContourFill& f : fill_contour_gaps(r.sequence)) {
    const std::string detail = fmt::format(
        "no {} contour in this frame: interpolated between frames {} and {} "
        "(weight {:.2f})",
        f.label, f.from_frame, f.to_frame, f.weight);
    r.repairs.push_back({f.frame, f.slice, -1, "contour-filled-in-time", detail, 0.0});
  }
}

// The slice alignment, the note on repairs, the smoothing and the frame times, for every input.
void finish_input(InputResult& result, const InputOptions& options) {
  fill_gaps_in_time(result, options);
  note_partial_slices(result);
  align_slices_on_request(result, options);
  smooth_traced_contours(result, options);
  if (!result.repairs.empty())
    result.notes.push_back(
        fmt::format("repaired {} contour flaw(s) instead of refusing the input (--strict refuses): "
                    "see report.json \"repairs\"",
                    result.repairs.size()));
  apply_frame_times(result, options);
}

void require_one_timing(const std::string& source, const InputOptions& options) {
  if (options.frame_ms > 0 && options.cycle_ms > 0)
    throw InvalidInput(ErrorCode::Usage, Location{source}, "give --frame-ms or --cycle-ms, not both");
}

}  // namespace

InputResult read_contours(const fs::path& input, const InputOptions& options) {
  require_one_timing(input.string(), options);
  InputResult result = read_any(input, options);
  finish_input(result, options);
  return result;
}

InputResult read_contour_list(std::vector<RawContour> contours, int frame_count, const std::vector<double>& times_ms,
                              const std::string& source, const InputOptions& options) {
  require_one_timing(source, options);
  InputResult result;
  result.format = "contours-in-memory";
  if (!options.strict) result.repairs = repair_contours(contours);
  result.sequence = build_sequence(contours, frame_count, times_ms, source, options.stack);
  if (!options.label.empty() && options.label != "all") {
    result.sequence = select_label(result.sequence, options.label);
    result.notes.push_back("label: only \"" + options.label + "\" kept");
  }
  finish_input(result, options);
  return result;
}

}  // namespace c4d
