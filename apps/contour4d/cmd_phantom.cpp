// `contour4d phantom`: writes an analytic phantom's contours and its true surface (docs/phantoms.md).
#include <cmath>
#include <filesystem>
#include <unistd.h>
#include <iostream>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "contour4d/core/errors.h"
#include "contour4d/io/contours_json.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/io/images.h"
#include "contour4d/phantoms/phantom.h"
#include "contour4d/phantoms/rasterize.h"

namespace c4d::cli {

namespace {

struct PhantomArgs {
  std::string name;
  std::string out;
  bool list = false;
  PhantomOptions options;
  std::string mask;                  // label image to write ("" = none)
  std::vector<double> mask_spacing;  // X,Y (in-plane voxel size, mm) or X,Y,Z (Z sets the slice spacing)
  int mask_label = 1;
};

std::string catalogue_text() {
  std::string s;
  for (const std::string& n : phantom_names()) s += fmt::format("  {:<18}{}\n", n, phantom_description(n));
  return s;
}

std::string truth_json(const Phantom& ph, const PhantomOptions& o) {
  nlohmann::ordered_json j;
  j["format"] = "contour4d-phantom-truth";
  j["version"] = 1;
  j["phantom"] = ph.name;
  j["description"] = ph.description;
  j["units"] = "mm";
  j["space"] = o.oblique ? "phantom frame moved by the oblique rigid motion (docs/phantoms.md)" : "phantom frame";
  j["parameters"] = {
      {"spacing_mm", o.spacing},
      {"offset_mm", std::isnan(o.offset) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.offset)},
      {"frames", ph.truth.size()},
      {"oblique", o.oblique},
      {"truth_edge_mm", o.truth_edge}};
  j["slab"] = {{"normal", {ph.contours.normal.x, ph.contours.normal.y, ph.contours.normal.z}},
               {"min_offset_mm", ph.slab_min},
               {"max_offset_mm", ph.slab_max}};
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  for (std::size_t f = 0; f < ph.truth.size(); ++f) {
    std::size_t contours = 0;
    for (const Slice& s : ph.contours.frames[f].slices) contours += s.contours.size();
    frames.push_back({{"frame", f},
                      {"time_ms", ph.contours.frames[f].time_ms},
                      {"volume_mm3", ph.true_volume_mm3[f]},
                      {"mesh_volume_mm3", signed_volume(ph.truth[f])},
                      {"vertices", ph.truth[f].positions.size()},
                      {"triangles", ph.truth[f].triangles.size()},
                      {"slices", ph.contours.frames[f].slices.size()},
                      {"contours", contours},
                      {"shape_parameters", ph.shape_parameters[f]}});
  }
  j["frames"] = frames;
  return j.dump(2) + "\n";
}

// ITK writes in place: write beside the target under a temporary name (same extension), then rename.
void write_mask_atomic(const std::string& file, const std::vector<LabelVolume>& mask) {
  namespace fs = std::filesystem;
  const fs::path target(file);
  const fs::path tmp =
      target.parent_path() / (".c4d-tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  try {
    write_label_volume(tmp, mask);
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

int run_phantom(const PhantomArgs& a) {
  if (a.list || a.name.empty()) {
    std::cout << "Phantoms:\n" << catalogue_text();
    if (!a.list)
      throw InvalidInput(ErrorCode::Usage, {}, "no phantom named",
                         "give a name, e.g. `contour4d phantom left-heart -o lh`");
    return 0;
  }
  if (a.out.empty() && a.mask.empty())
    throw InvalidInput(ErrorCode::Usage, {}, "no output", "give -o DIR and/or --mask FILE.nii.gz");
  PhantomOptions po = a.options;
  RasterizeOptions ro;
  ro.label = a.mask_label;
  if (!a.mask_spacing.empty()) {
    if (a.mask_spacing.size() != 2 && a.mask_spacing.size() != 3)
      throw InvalidInput(ErrorCode::Usage, {}, "--mask-spacing takes X,Y or X,Y,Z", "e.g. --mask-spacing 1,1,8");
    ro.pixel_x = a.mask_spacing[0];
    ro.pixel_y = a.mask_spacing[1];
    if (a.mask_spacing.size() == 3) po.spacing = a.mask_spacing[2];
  }
  if (!a.mask.empty() && !is_label_image_file(a.mask))
    throw InvalidInput(ErrorCode::Usage, {}, "--mask " + a.mask + ": unknown image extension",
                       "use .nii.gz, .nii, .nrrd or .mha");
  const Phantom ph = make_phantom(a.name, po);
  std::vector<LabelVolume> mask;
  if (!a.mask.empty()) mask = rasterize_phantom(ph, ro);  // validate everything before writing
  if (a.out.empty()) {
    write_mask_atomic(a.mask, mask);
    const LabelVolume& v = mask.front();
    std::cout << fmt::format(
        "phantom {}: wrote mask {} ({}x{}x{} voxels of {:.3g}x{:.3g}x{:.3g} mm, {} frame(s), label {})\n", ph.name,
        a.mask, v.dims[0], v.dims[1], v.dims[2], v.spacing[0], v.spacing[1], v.spacing[2], mask.size(), ro.label);
    return 0;
  }
  OutputDir out(a.out);
  out.write("contours.json", format_contours_json(ph.contours));
  {
    OutputDir truth(out.path("truth"));
    MeshFrames frames;
    frames.meshes = ph.truth;
    for (const Frame& f : ph.contours.frames) frames.times_ms.push_back(f.time_ms);
    write_mesh_frames(truth, frames, "contour4d phantom " + ph.name + " ground truth (mm)", MeshFormats{.obj = true});
    truth.write("truth.json", truth_json(ph, po));
    truth.commit();
  }
  out.commit();
  if (!a.mask.empty()) write_mask_atomic(a.mask, mask);

  std::size_t contours = 0, triangles = 0;
  for (const Frame& f : ph.contours.frames)
    for (const Slice& s : f.slices) contours += s.contours.size();
  for (const TriangleMesh& m : ph.truth) triangles += m.triangles.size();
  std::cout << fmt::format("phantom {}: {}\n", ph.name, ph.description);
  std::cout << fmt::format(
      "  {} frame(s), {} contours, slice planes {:.2f} .. {:.2f} mm along ({:.3f}, {:.3f}, {:.3f})\n", ph.truth.size(),
      contours, ph.slab_min, ph.slab_max, ph.contours.normal.x, ph.contours.normal.y, ph.contours.normal.z);
  double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
  for (double v : ph.true_volume_mm3) vmin = std::min(vmin, v), vmax = std::max(vmax, v);
  std::cout << fmt::format("  true volume {:.1f} .. {:.1f} mL, truth {} triangles in all\n", vmin / 1000, vmax / 1000,
                           triangles);
  std::cout << fmt::format("  wrote {}/contours.json and {}/truth/ (mesh.pvd, frames/, truth.json)\n", a.out, a.out);
  if (!a.mask.empty()) {
    const LabelVolume& v = mask.front();
    std::cout << fmt::format(
        "  wrote mask {}: {}x{}x{} voxels of {:.3g}x{:.3g}x{:.3g} mm, {} frame(s), label {}; "
        "voxel k = slice id\n",
        a.mask, v.dims[0], v.dims[1], v.dims[2], v.spacing[0], v.spacing[1], v.spacing[2], mask.size(), ro.label);
  }
  return 0;
}

}  // namespace

void add_phantom_command(CLI::App& root, std::vector<Command>& commands) {
  auto args = std::make_shared<PhantomArgs>();
  CLI::App* app = root.add_subcommand(
      "phantom",
      "Write an analytic phantom: its contours (contours.json) and its true surface per frame (truth/).\n"
      "Every contour lies exactly on the truth mesh (its vertices and edges are truth vertices and edges).\n"
      "Coordinates in mm in the phantom's own frame (docs/phantoms.md).");
  app->footer(
      "Phantoms:\n" + catalogue_text() +
      "\nExamples:\n"
      "  contour4d phantom --list\n"
      "  contour4d phantom left-heart -o lh                 # ED, ES, ED; slices y = 32.5 - 5k\n"
      "  contour4d phantom ellipsoid -o el --frames 10 --spacing 8\n"
      "  contour4d phantom torus -o tor --oblique           # rotated 30 deg about (1,2,3), moved (12,-7,33)\n"
      "  contour4d phantom left-heart-cycle -o lh --oblique --mask lh/mask.nii.gz --mask-spacing 1,1,8\n"
      "                                                     # + a 4D label image sampled on the slice planes\n");
  app->add_option("name", args->name, "phantom name (see --list)");
  app->add_option("-o,--output", args->out, "output folder (replaced atomically)");
  app->add_flag("--list", args->list, "list the phantoms and exit");
  app->add_option("--spacing", args->options.spacing, "distance between slice planes (mm)")->capture_default_str();
  app->add_option("--offset", args->options.offset,
                  "height of one slice plane on the slice axis (mm; default per phantom)");
  app->add_option("--frames", args->options.frames, "frames of a cyclic phantom (0: its default)")
      ->capture_default_str();
  app->add_flag("--oblique", args->options.oblique, "apply the fixed oblique rigid motion to contours and truth");
  app->add_option("--truth-edge", args->options.truth_edge, "target edge length of the truth mesh (mm)")
      ->capture_default_str();
  app->add_option("--mask", args->mask,
                  "also write the phantom as a label image (.nii.gz, .nii, .nrrd, .mha; 4D for several frames): "
                  "voxel centres inside the analytic surface, slices on the phantom's slice planes");
  app->add_option("--mask-spacing", args->mask_spacing,
                  "mask voxel size X,Y (in-plane, mm; default 1,1) or X,Y,Z (Z sets --spacing)")
      ->delimiter(',');
  app->add_option("--mask-label", args->mask_label, "label value of the mask")->capture_default_str();
  commands.push_back({app, [args] { return run_phantom(*args); }});
}

}  // namespace c4d::cli
