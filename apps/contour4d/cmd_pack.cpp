// `contour4d pack` and `contour4d unpack`: the compact 4D model (docs/compact.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "cli.h"
#include "contour4d/core/errors.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/temporal/model_c4d.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/pipeline/pack_run.h"
#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/sequence.h"

namespace c4d::cli {
namespace {

struct PackArgs {
  std::string input;
  std::string output;
  PackRunOptions pack;
};

int run_pack(const PackArgs& a) {
  const std::filesystem::path in(a.input);
  const PackRun run = pack_run(load_mesh_sequence(in), a.pack);
  const CompactStats& st = run.stats;
  const std::filesystem::path dir = std::filesystem::is_directory(in) ? in : in.parent_path();
  const std::filesystem::path out = a.output.empty() ? dir / "model.c4d" : std::filesystem::path(a.output);
  write_file_atomic(out, run.c4d);
  const std::size_t nv = run.input.positions[0].size(), nt = run.input.triangles.size(),
                    nf = run.input.positions.size();
  const std::size_t bytes = run.c4d.size();
  // Per-frame baselines: our VTP writer (Float64 points, Int64 connectivity and offsets) and a
  // binary PLY (float32 xyz, uchar count + 3 int32 per face), headers not counted.
  const double vtp = static_cast<double>(nv * 24 + nt * 32) * static_cast<double>(nf);
  const double ply = static_cast<double>(nv * 12 + nt * 13) * static_cast<double>(nf);
  std::cout << fmt::format("packed {} frames, {} vertices, {} triangles into {} ({} bytes)\n", nf, nv, nt, out.string(),
                           bytes)
            << fmt::format(
                   "  zstd level {}: payload {} B before compression, {} B stored ({:.2f}x); file {} B with the "
                   "{}-byte header\n",
                   ModelC4dWriteOptions{}.level, run.raw_payload, run.stored_payload,
                   static_cast<double>(run.raw_payload) / static_cast<double>(run.stored_payload), bytes,
                   kModelC4dHeaderBytes)
            << fmt::format(
                   "  parts before compression: connectivity {} B, frame-0 positions {} B, motion of the other "
                   "frames {} B (grid step {:.4f} mm)\n",
                   st.index_bytes, st.position_bytes, st.motion_bytes, run.model.step)
            << fmt::format(
                   "  error vs input: vertex to same vertex max {:.4f} mm, RMS {:.4f} mm (bound {:.4f} mm); facet "
                   "normals p99 {:.2f}° in the worst frame, max {:.2f}°\n",
                   st.max_error, st.rms_error, run.model.tolerance, st.normal_p99, st.normal_max)
            << fmt::format("  per-frame meshes: VTP {:.0f} B ({:.0f}x larger), binary PLY {:.0f} B ({:.0f}x larger)\n",
                           vtp, vtp / static_cast<double>(bytes), ply, ply / static_cast<double>(bytes));
  if (!run.glb.empty()) {
    const std::filesystem::path gp = std::filesystem::path(out).replace_extension(".glb");
    write_file_atomic(gp, run.glb);
    std::cout << fmt::format("  glTF {} ({} bytes, {} morph targets, metres, Y up)\n", gp.string(), run.glb.size(), nf);
  }
  return 0;
}

struct UnpackArgs {
  std::string input;
  std::string output;
  std::size_t resample = 0;
  std::string interp = "catmull-rom";
  std::string format = "vtp";
};

int run_unpack(const UnpackArgs& a) {
  const MeshSequence seq = resample_if(read_model_c4d_sequence(a.input), a.resample, a.interp);
  OutputDir out(a.output);
  write_mesh_sequence(out, seq, "unpacked from " + std::filesystem::path(a.input).filename().string(),
                      parse_mesh_formats(a.format));
  out.commit();
  std::cout << fmt::format("unpacked {} frames ({} vertices, {} triangles) into {}\n", seq.positions.size(),
                           seq.positions[0].size(), seq.triangles.size(), a.output);
  return 0;
}

}  // namespace

void add_pack_command(CLI::App& root, std::vector<Command>& commands) {
  CLI::App* app = root.add_subcommand(
      "pack",
      "Store a 4D mesh compactly (Miara et al. Table I): the mesh of frame 0 once, then every frame's\n"
      "move, all on one grid, so every vertex of every frame is within --tolerance mm of the input\n"
      "(0.011 mm on the default grid) and the facet normals within --normal-p99 degrees (refining the\n"
      "grid where small triangles need it): the surfaces shade like the input. Writes model.c4d\n"
      "(zstd-compressed) and model.glb (glTF 2.0 with one morph target per frame and an animation,\n"
      "metres, Y up). Vertex ids are reordered for compression.");
  app->footer(
      "Examples:\n"
      "  contour4d pack out                         # out/model.c4d + out/model.glb\n"
      "  contour4d pack out --tolerance 0.02 -o lv.c4d\n"
      "  contour4d pack out --normal-p99 3 --step 0.025   # smaller file, coarser grid, normals within 3°\n"
      "  contour4d pack out --resample 60 --interp catmull-rom   # 60 frames over the cycle\n");
  auto args = std::make_shared<PackArgs>();
  app->add_option("INPUT", args->input, "output folder of a reconstruction (mesh.pvd, frames/) or a model.c4d")
      ->required();
  app->add_option("-o,--output", args->output, "model file (default INPUT/model.c4d); the .glb goes beside it");
  app->add_option("--tolerance", args->pack.tolerance, "max error of any vertex in any frame (mm)")
      ->default_val(0.05)
      ->check(CLI::PositiveNumber);
  app->add_option("--normal-p99", args->pack.normal_p99,
                  "bound on the angle between decoded and input facet normals, 99th percentile of the worst frame "
                  "(degrees)")
      ->default_val(1.5)
      ->check(CLI::PositiveNumber);
  app->add_option("--step", args->pack.step, "coarsest grid step tried (mm)")
      ->default_val(0.0125)
      ->check(CLI::PositiveNumber);
  app->add_option("--resample", args->pack.resample, "resample to N frames before packing (0: keep)")->default_val(0);
  app->add_option("--interp", args->pack.interp, "interpolation for --resample")
      ->check(CLI::IsMember({"linear", "catmull-rom", "step"}))
      ->default_val("catmull-rom");
  app->add_flag_callback(
      "--no-gltf", [args] { args->pack.gltf = false; }, "do not write the .glb");
  app->add_flag("--gltf-step", args->pack.gltf_step, "STEP animation in the .glb instead of LINEAR");
  app->add_flag("--gltf-quantized", args->pack.gltf_quantized,
                "a compact .glb (KHR_mesh_quantization, no normals) instead of the plain one every glTF reader loads");
  commands.push_back({app, [args] { return run_pack(*args); }});
}

void add_unpack_command(CLI::App& root, std::vector<Command>& commands) {
  CLI::App* app =
      root.add_subcommand("unpack", "Restore per-frame meshes (mesh.pvd, frames/*.vtp, *.obj) from a model.c4d.");
  app->footer(
      "Examples:\n"
      "  contour4d unpack out/model.c4d -o restored\n"
      "  contour4d unpack out/model.c4d -o smooth --resample 50 --interp catmull-rom\n");
  auto args = std::make_shared<UnpackArgs>();
  app->add_option("MODEL", args->input, "a model.c4d written by `contour4d pack`")->required();
  app->add_option("-o,--output", args->output, "output folder")->required();
  app->add_option("--format", args->format, "mesh files per frame: vtp (with mesh.pvd, always) and obj, e.g. vtp,obj")
      ->capture_default_str();
  app->add_option("--resample", args->resample, "resample to N frames (0: keep)")->default_val(0);
  app->add_option("--interp", args->interp, "interpolation for --resample")
      ->check(CLI::IsMember({"linear", "catmull-rom", "step"}))
      ->default_val("catmull-rom");
  commands.push_back({app, [args] { return run_unpack(*args); }});
}

}  // namespace c4d::cli
