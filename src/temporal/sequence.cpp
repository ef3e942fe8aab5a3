// Inputs of the compact model and playback: an output folder, a model.c4d, or a synthetic beating
// ellipsoid whose motion (pulsation with a cardiac volume curve, twist, sway) stands in for a left
// ventricle in tests and benchmarks (Miara et al. §IV used a 20-frame 512×512×38 sequence).
#include "contour4d/temporal/sequence.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "contour4d/core/errors.h"
#include "contour4d/temporal/model_c4d.h"
#include "contour4d/temporal/compact.h"

namespace c4d {

MeshSequence to_mesh_sequence(const MeshFrames& frames, const std::string& source) {
  if (frames.meshes.empty())
    throw InvalidInput(ErrorCode::BadMesh, {source}, "no mesh frames",
                       "pass a folder written by `contour4d reconstruct`");
  MeshSequence seq;
  seq.triangles = frames.meshes[0].triangles;
  for (std::size_t f = 0; f < frames.meshes.size(); ++f) {
    const TriangleMesh& m = frames.meshes[f];
    if (m.positions.size() != frames.meshes[0].positions.size() || m.triangles != seq.triangles)
      throw InvalidInput(
          ErrorCode::BadMesh, {source, -1, static_cast<int>(f)},
          "frame " + std::to_string(f) + " does not share frame 0's vertices and triangles (" +
              std::to_string(m.positions.size()) + " vs " + std::to_string(frames.meshes[0].positions.size()) +
              " vertices)",
          "pack and export need a 4D mesh with vertex correspondence (the output of `contour4d reconstruct`), "
          "not independent per-frame meshes");
    seq.positions.push_back(m.positions);
  }
  seq.times_ms = frames.times_ms;
  if (seq.times_ms.size() != seq.positions.size()) {
    seq.times_ms.clear();
    for (std::size_t f = 0; f < seq.positions.size(); ++f) seq.times_ms.push_back(static_cast<double>(f));
  }
  return seq;
}

MeshSequence load_mesh_sequence(const std::filesystem::path& path) {
  if (std::filesystem::is_regular_file(path)) return read_model_c4d_sequence(path);
  return to_mesh_sequence(read_mesh_frames(path), path.string());
}

MeshSequence synthetic_beating_mesh(int subdivisions, std::size_t frames) {
  // Icosahedron, then midpoint subdivision projected to the unit sphere.
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> p = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  std::vector<Triangle> t = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& v : p) v = normalized(v);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const std::pair<std::uint32_t, std::uint32_t> key{std::min(a, b), std::max(a, b)};
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back(normalized(p[a] + p[b]));
      const auto id = static_cast<std::uint32_t>(p.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<Triangle> next;
    next.reserve(t.size() * 4);
    for (const Triangle& tri : t) {
      const std::uint32_t ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    t = std::move(next);
  }
  MeshSequence seq;
  seq.triangles = t;
  const double pi = std::numbers::pi;
  for (std::size_t f = 0; f < frames; ++f) {
    const double phase = static_cast<double>(f) / static_cast<double>(frames);  // 0..1 over the cycle
    // Cardiac-like radius factor: fast ejection to end-systole at 35 %, then filling.
    const double ejection =
        phase < 0.35 ? 0.5 - 0.5 * std::cos(pi * phase / 0.35) : 0.5 + 0.5 * std::cos(pi * (phase - 0.35) / 0.65);
    const double radial = 1.0 - 0.12 * ejection;  // ~30 % volume change
    const double axial = 1.0 - 0.06 * ejection;
    const double twist = 0.25 * ejection;  // rad at the apex/base extremes
    const double sway = 2.0 * std::sin(2.0 * pi * phase);
    std::vector<Vec3> pos(p.size());
    for (std::size_t v = 0; v < p.size(); ++v) {
      const Vec3 u = p[v];
      const double z = 45.0 * axial * u.z;
      const double a = twist * u.z;
      const double x = 30.0 * radial * u.x, y = 30.0 * radial * u.y;
      pos[v] = {x * std::cos(a) - y * std::sin(a) + sway, x * std::sin(a) + y * std::cos(a) + 0.5 * sway * u.z, z};
    }
    seq.positions.push_back(std::move(pos));
    seq.times_ms.push_back(1000.0 * phase);
  }
  return seq;
}

}  // namespace c4d
