// Several structures in one run (structures_run.h).
#include "contour4d/pipeline/structures_run.h"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

using Json = nlohmann::ordered_json;

Json structure_json(const StructureRun& r) {
  Json j;
  j["name"] = r.structure.name;
  j["frames"] = r.structure.frames;
  if (r.error_code != 0) {
    j["ok"] = false;
    j["exit_code"] = r.error_code;
    j["error"] = r.error;
    return j;
  }
  const Json s = Json::parse(r.run.report)["summary"];
  j["ok"] = true;
  for (const char* key :
       {"volume_ml", "ed_frame", "es_frame", "edv_ml", "esv_ml", "ef_percent", "vertices", "triangles", "method"})
    j[key] = s[key];
  // ED and ES as input frames (a structure may lack some frames).
  j["ed_frame"] = r.structure.frames[s["ed_frame"].get<std::size_t>()];
  j["es_frame"] = r.structure.frames[s["es_frame"].get<std::size_t>()];
  if (r.structure.wall) {  // the wall's own report holds its mass per frame
    j["mass_g"] = s["mass_g"];
    j["density_g_per_ml"] = kMyocardiumDensity;
  }
  j["notes"] = r.structure.input.notes;
  return j;
}

}  // namespace

std::vector<StructureRun> reconstruct_structures(std::vector<Structure> structures, const std::string& input_name,
                                                 const ReconstructRunOptions& options, const ProgressFn& progress,
                                                 const RunMessage& say) {
  std::vector<StructureRun> runs;
  for (Structure& st : structures) {
    StructureRun r;
    r.structure = std::move(st);
    if (say) say(fmt::format("  structure {}: {} frames", r.structure.name, r.structure.frames.size()));
    ReconstructRunOptions o = options;
    o.label = r.structure.name;
    try {
      r.run = reconstruct_run(r.structure.input, input_name, o, progress, say);
      if (!r.run.check.ok()) {
        r.error_code = static_cast<int>(ErrorCode::InvalidResult);
        r.error = "failed its checks: " + r.run.check.summary();
      }
    } catch (const Error& e) {
      r.error_code = static_cast<int>(e.code());
      r.error = e.what();
    }
    if (say && r.error_code != 0)
      say(fmt::format("  structure {}: not written (exit code {}): {}", r.structure.name, r.error_code, r.error));
    runs.push_back(std::move(r));
  }
  return runs;
}

std::string structures_report(const std::vector<StructureRun>& runs, const std::string& input_name,
                              const std::vector<std::string>& notes) {
  Json summary;
  summary["input"] = input_name;
  summary["structures"] = Json::array();
  for (const StructureRun& r : runs) summary["structures"].push_back(structure_json(r));
  Json report;
  report["summary"] = summary;
  report["tool"] = "contour4d 0.1.0";
  report["units"] = "mm";
  report["notes"] = notes;
  return report.dump(2) + "\n";
}

void write_structures(OutputDir& out, const std::vector<StructureRun>& runs, const MeshFormats& formats,
                      const std::string& report) {
  for (const StructureRun& r : runs) {
    if (r.error_code != 0) continue;
    OutputDir sub(out.path(r.structure.name));
    write_run(sub, r.run, formats);
  }
  out.write("report.json", report);
  out.commit();
}

}  // namespace c4d
