// The VaMPy / OasisMove hand-off (A. Bergersen, H. Kjeldsberg et al., VaMPy, JOSS 2023; OasisMove, H. A.
// Kjeldsberg et al. 2023): a surface per step with the same triangles, the moving-atrium input of VaMPy's
// automated preprocessing, which reads the moved surfaces in name order over one cycle.
#include "contour4d/solver/vampy.h"

#include <fmt/format.h>

#include "contour4d/io/vtk_grid.h"

namespace c4d {

void write_vampy(const OutputDir& out, const std::string& folder, const Handoff& h, double length_scale) {
  const FacePart wall = face_part(h, 0);
  std::vector<std::uint32_t> local(h.surface.seq.positions.front().size(), 0);
  for (std::uint32_t i = 0; i < wall.vertices.size(); ++i) local[wall.vertices[i]] = i;
  std::vector<Triangle> triangles;
  triangles.reserve(wall.triangles.size());
  for (std::uint32_t t : wall.triangles) {
    const Triangle& tri = h.surface.seq.triangles[t];
    triangles.push_back({local[tri[0]], local[tri[1]], local[tri[2]]});
  }
  const std::size_t steps = h.steps.times_s.size();
  const int width = std::max(2, static_cast<int>(fmt::format("{}", steps - 1).size()));
  auto write = [&](const std::string& name, std::size_t step) {
    const std::vector<Vec3> x = surface_at(h, step);
    std::vector<Vec3> p;
    p.reserve(wall.vertices.size());
    for (std::uint32_t v : wall.vertices) p.push_back(length_scale * x[v]);
    out.write(folder + "/" + name,
              format_vtp_data(p, triangles, {},
                              fmt::format("contour4d export for VaMPy: wall at t = {} s, lengths in {} mm",
                                          h.steps.times_s[step], 1.0 / length_scale)));
  };
  write("model.vtp", 0);
  for (std::size_t i = 0; i < steps; ++i) write(fmt::format("model_moved_{:0{}}.vtp", i, width), i);
}

}  // namespace c4d
