// Remeshing for triangle quality: Lim et al. 2014, "Surface Smoothing and Refinement" refines the
// coarse surface; we use CGAL's isotropic remeshing (Botsch & Kobbelt 2004, "A remeshing approach
// to multiresolution modeling") with the input contours as constrained polylines, so they remain
// chains of mesh edges (split only, never moved) and conformity stays exact.
#include "contour4d/surface/refine.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>

namespace c4d {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

void remesh_isotropic(TriangleMesh& mesh, std::vector<std::array<std::uint32_t, 2>>& constrained,
                      std::vector<char>& fixed, const RemeshOptions& options) {
  Mesh sm;
  std::vector<Mesh::Vertex_index> vid;
  vid.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) vid.push_back(sm.add_vertex(K::Point_3(p.x, p.y, p.z)));
  for (const Triangle& t : mesh.triangles)
    if (sm.add_face(vid[t[0]], vid[t[1]], vid[t[2]]) == Mesh::null_face()) return;  // not manifold: leave as is
  auto ecm = sm.add_property_map<Mesh::Edge_index, bool>("e:c4d_constrained", false).first;
  auto vcm = sm.add_property_map<Mesh::Vertex_index, bool>("v:c4d_fixed", false).first;
  for (const auto& e : constrained) {
    const auto h = sm.halfedge(vid[e[0]], vid[e[1]]);
    if (h != Mesh::null_halfedge()) ecm[sm.edge(h)] = true;
  }
  fixed.resize(mesh.positions.size(), 0);
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (fixed[i]) vcm[vid[i]] = true;
  PMP::isotropic_remeshing(faces(sm), options.edge, sm,
                           CGAL::parameters::number_of_iterations(static_cast<unsigned>(options.iterations))
                               .edge_is_constrained_map(ecm)
                               .vertex_is_constrained_map(vcm)
                               .protect_constraints(!options.split_constraints)
                               .collapse_constraints(false)
                               .relax_constraints(false));
  sm.collect_garbage();
  // Back to plain arrays; vertices in Surface_mesh order (old ones keep their relative order).
  TriangleMesh out;
  std::vector<std::uint32_t> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), 0);
  std::vector<char> out_fixed;
  for (auto v : sm.vertices()) {
    index[v] = static_cast<std::uint32_t>(out.positions.size());
    const auto& p = sm.point(v);
    out.positions.push_back({p.x(), p.y(), p.z()});
    out_fixed.push_back(vcm[v] ? 1 : 0);
  }
  for (auto f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : vertices_around_face(sm.halfedge(f), sm)) t[k++] = index[v];
    out.triangles.push_back(t);
  }
  constrained.clear();
  for (auto e : sm.edges()) {
    if (!ecm[e]) continue;
    const std::uint32_t a = index[sm.vertex(e, 0)], b = index[sm.vertex(e, 1)];
    constrained.push_back({std::min(a, b), std::max(a, b)});
    out_fixed[a] = out_fixed[b] = 1;  // split points of contour edges lie on the contour: keep them
  }
  std::sort(constrained.begin(), constrained.end());
  mesh = std::move(out);
  fixed = std::move(out_fixed);
}

}  // namespace c4d
