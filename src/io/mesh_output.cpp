#include "contour4d/io/mesh_output.h"

#include <algorithm>

#include <fmt/format.h>

#include "contour4d/core/errors.h"
#include "contour4d/io/obj.h"
#include "contour4d/io/vtk_xml.h"

namespace c4d {
namespace fs = std::filesystem;

MeshFormats parse_mesh_formats(const std::string& list) {
  MeshFormats formats;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, end - start);
    if (name == "obj")
      formats.obj = true;
    else if (name != "vtp" && name != "pvd")
      throw InvalidInput(ErrorCode::Usage, Location{}, "unknown mesh format \"" + name + "\"",
                         "--format takes a comma-separated list of vtp (always written, with mesh.pvd) and obj");
    start = end + 1;
  }
  return formats;
}

void write_mesh_frames(const OutputDir& out, const MeshFrames& frames, const std::string& comment,
                       const MeshFormats& formats) {
  std::vector<PvdEntry> entries;
  for (std::size_t f = 0; f < frames.meshes.size(); ++f) {
    const std::string stem = fmt::format("frames/frame_{:03d}", f);
    const double t = f < frames.times_ms.size() ? frames.times_ms[f] : static_cast<double>(f);
    out.write(stem + ".vtp", format_vtp(frames.meshes[f]));
    if (formats.obj)
      out.write(stem + ".obj",
                format_obj(frames.meshes[f], comment.empty() ? fmt::format("frame {}, t = {} ms", f, t)
                                                             : fmt::format("{}; frame {}, t = {} ms", comment, f, t)));
    entries.push_back({t, stem + ".vtp"});
  }
  out.write("mesh.pvd", format_pvd(entries));
}

void write_mesh_sequence(const OutputDir& out, const MeshSequence& seq, const std::string& comment,
                         const MeshFormats& formats) {
  MeshFrames frames;
  frames.times_ms = seq.times_ms;
  for (std::size_t f = 0; f < seq.positions.size(); ++f) frames.meshes.push_back(seq.frame(f));
  write_mesh_frames(out, frames, comment, formats);
}

MeshFrames read_mesh_frames(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec))
    throw IoError(ErrorCode::FileNotFound, Location{dir.string()}, "output folder not found",
                  "Give a folder written by `contour4d reconstruct` or `contour4d phantom` (its truth/ folder)");
  MeshFrames frames;
  if (fs::is_regular_file(dir / "mesh.pvd", ec)) {
    const std::string pvd = (dir / "mesh.pvd").string();
    for (const PvdEntry& e : parse_pvd(read_file(pvd), pvd)) {
      const fs::path f = dir / e.file;
      frames.meshes.push_back(parse_vtp(read_file(f), f.string()));
      frames.times_ms.push_back(e.time_ms);
    }
    return frames;
  }
  // No collection: take frames/frame_*.vtp, else frames/frame_*.obj, in name order.
  for (const char* ext : {".vtp", ".obj"}) {
    std::vector<fs::path> files;
    if (fs::is_directory(dir / "frames", ec))
      for (const auto& entry : fs::directory_iterator(dir / "frames", ec))
        if (entry.path().extension() == ext && entry.path().filename().string().rfind("frame_", 0) == 0)
          files.push_back(entry.path());
    if (files.empty()) continue;
    std::sort(files.begin(), files.end());
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::string content = read_file(files[i]);
      frames.meshes.push_back(std::string(ext) == ".vtp" ? parse_vtp(content, files[i].string())
                                                         : parse_obj(content, files[i].string()));
      frames.times_ms.push_back(static_cast<double>(i));
    }
    return frames;
  }
  throw IoError(ErrorCode::FileNotFound, Location{dir.string()}, "no mesh.pvd and no frames/frame_*.vtp or .obj",
                "Give a folder written by `contour4d reconstruct` or `contour4d phantom`");
}

}  // namespace c4d
