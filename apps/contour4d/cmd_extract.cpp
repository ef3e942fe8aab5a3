// `contour4d extract`: reads any supported contour input, validates it as a stack of parallel
// slices, and writes it as contour4d JSON (docs/formats.md) with a summary of what was used.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include <fmt/format.h>

#include "cli.h"
#include "input_options.h"
#include "contour4d/core/errors.h"
#include "contour4d/io/contours_json.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/io/output_dir.h"

namespace c4d::cli {

namespace {

struct ExtractArgs {
  std::string input;
  std::string out;
  InputOptions in;
};

std::string summary(const InputResult& r, const std::string& out) {
  const Sequence& seq = r.sequence;
  std::string s = fmt::format("read {} ({})\n", seq.source, r.format);
  for (const std::string& n : r.notes) s += "  " + n + "\n";
  std::set<int> ids;
  std::size_t total = 0;
  for (const Frame& f : seq.frames)
    for (const Slice& sl : f.slices) {
      ids.insert(sl.id);
      total += sl.contours.size();
    }
  s += fmt::format("frames: {}, slices: {}, contours: {}, space: {}, units: {}\n", seq.frames.size(), ids.size(), total,
                   seq.space, seq.units);
  s += fmt::format("stack normal: ({:.4f}, {:.4f}, {:.4f})\n", seq.normal.x, seq.normal.y, seq.normal.z);
  // Offsets of every slice id (the same in every frame) and their spacing.
  std::vector<std::pair<double, int>> offsets;
  for (int id : ids)
    for (const Frame& f : seq.frames) {
      const auto it = std::find_if(f.slices.begin(), f.slices.end(), [&](const Slice& sl) { return sl.id == id; });
      if (it != f.slices.end()) {
        offsets.emplace_back(it->offset, id);
        break;
      }
    }
  std::sort(offsets.begin(), offsets.end());
  std::string offs;
  for (const auto& [o, id] : offsets) offs += fmt::format("{}{}@{:.2f}", offs.empty() ? "" : " ", id, o);
  s += "slices (id@offset mm, base to apex as given): " + offs + "\n";
  if (offsets.size() >= 2) {
    double lo = 1e300, hi = 0;
    for (std::size_t k = 1; k < offsets.size(); ++k) {
      lo = std::min(lo, offsets[k].first - offsets[k - 1].first);
      hi = std::max(hi, offsets[k].first - offsets[k - 1].first);
    }
    s += std::abs(hi - lo) < 0.01 ? fmt::format("slice spacing: {:.2f} mm\n", lo)
                                  : fmt::format("slice spacing: {:.2f} to {:.2f} mm\n", lo, hi);
  }
  s += "frame  time_ms  slices  contours  slice ids\n";
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    std::size_t n = 0;
    std::string list;
    for (const Slice& sl : seq.frames[f].slices) {
      n += sl.contours.size();
      list += (list.empty() ? "" : ",") + std::to_string(sl.id);
    }
    s += fmt::format("{:>5}  {:>7.1f}  {:>6}  {:>8}  {}\n", f, seq.frames[f].time_ms, seq.frames[f].slices.size(), n,
                     list);
  }
  s += "wrote " + out + "\n";
  return s;
}

int run_extract(const ExtractArgs& a) {
  const InputResult r = read_contours(a.input, a.in);
  write_file_atomic(a.out, format_contours_json(r.sequence));
  std::cout << summary(r, a.out);
  return 0;
}

}  // namespace

void add_extract_command(CLI::App& root, std::vector<Command>& commands) {
  auto args = std::make_shared<ExtractArgs>();
  CLI::App* app = root.add_subcommand(
      "extract",
      "Read contours (contour4d JSON, a biv-me GPFile folder, a Sunnybrook patient folder, a DICOM RT structure set,\n"
      "or label images:\n"
      "NIfTI/NRRD/MetaImage masks, contours extracted by marching squares), validate them as a stack of\n"
      "parallel slices, and write them as contour4d JSON (mm, patient space; docs/formats.md, docs/images.md).");
  app->add_option("input", args->input,
                  "contour JSON, GPFile folder, Sunnybrook folder, RT structure set (.dcm), or label image(s)")
      ->required();
  app->add_option("-o,--output", args->out, "contour JSON file to write")->required();
  add_input_options(app, args->in);
  app->footer(
      "Examples:\n"
      "  contour4d phantom left-heart -o lh && contour4d extract lh/contours.json -o lv.json   # runs anywhere\n"
      "  contour4d extract patient1/guidepoints -o lv.json                       # a biv-me GPFile folder\n"
      "  contour4d extract patient1 --type SAX_LV_ENDOCARDIAL --type SAX_LV_EPICARDIAL -o lv2.json\n"
      "  contour4d extract lv2.json --label lv-epi -o epi.json\n"
      "  contour4d extract SC-HF-I-1 --label all -o sb.json      # a Sunnybrook folder: endo- and epicardium\n"
      "  contour4d extract RS.dcm -o rois.json                   # an RT structure set: every ROI, labelled by name\n"
      "  contour4d extract 'patient001_frame*_gt.nii.gz' --labels acdc --label lv -o lv.json\n"
      "Exit codes name the problem (10 file not found, 12 parse error, 15 degenerate contour, 27 no referenced frame\n"
      "of reference, 28 an empty ROI, ...; docs/cli.md).");
  commands.push_back({app, [args] { return run_extract(*args); }});
}

}  // namespace c4d::cli
