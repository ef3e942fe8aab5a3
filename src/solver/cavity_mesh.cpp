// The cavity's tetrahedral mesh by TetGen 1.5 (H. Si, ACM TOMS 41(2), 2015: constrained Delaunay
// tetrahedralisation of a piecewise linear complex, then Delaunay refinement for a radius-edge bound), asked to
// keep the boundary as given (-Y) so the flow faces and the wall keep the reconstruction's triangles and ids.
#define TETLIBRARY
#include "contour4d/solver/cavity_mesh.h"

#include <tetgen.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include <fmt/format.h>

#include "contour4d/core/errors.h"
#include "contour4d/metrics/topology.h"

namespace c4d {
namespace {

std::string tetgen_reason(int code) {
  switch (code) {
    case 1:
      return "out of memory";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "a very small feature of the surface (nearly touching triangles)";
    case 5:
      return "two surface triangles very close to each other";
    case 10:
      return "the input is invalid";
    default:
      return fmt::format("internal error {}", code);
  }
}

using FaceKey = std::array<std::uint32_t, 3>;
FaceKey sorted(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  FaceKey k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

// The tet whose face each surface triangle is; every triangle must be one.
std::vector<std::uint32_t> boundary_tets(const TetMesh& mesh) {
  std::map<FaceKey, std::uint32_t> face_tet;
  for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) {
    const Tet& q = mesh.tets[t];
    for (int k = 0; k < 4; ++k) face_tet[sorted(q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4])] = t;
  }
  std::vector<std::uint32_t> out;
  out.reserve(mesh.boundary.size());
  for (std::size_t i = 0; i < mesh.boundary.size(); ++i) {
    const Triangle& tri = mesh.boundary[i];
    const auto it = face_tet.find(sorted(tri[0], tri[1], tri[2]));
    if (it == face_tet.end())
      throw SolverError(
          ErrorCode::VolumeMeshFailed, {},
          fmt::format("surface triangle {} is not a face of the cavity mesh (TetGen changed the boundary)", i),
          "report this with the input");
    out.push_back(it->second);
  }
  return out;
}

// Splits every chord (an edge between two surface nodes that is not a surface edge) at its midpoint, a new
// inner node: a tet whose four nodes all lie on the wall moves with the wall alone, and where the wall bends it
// can invert whatever the extension does; split, each part has an inner node the extension places.
std::size_t split_chords(TetMesh& mesh, const std::vector<Triangle>& surface) {
  const std::size_t nb = mesh.surface_nodes;
  using Edge = std::pair<std::uint32_t, std::uint32_t>;
  auto key = [](std::uint32_t a, std::uint32_t b) { return Edge{std::min(a, b), std::max(a, b)}; };
  std::set<Edge> wall;
  for (const Triangle& t : surface)
    for (int k = 0; k < 3; ++k) wall.insert(key(t[k], t[(k + 1) % 3]));
  std::set<Edge> chords;
  for (const Tet& q : mesh.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (q[i] < nb && q[j] < nb && !wall.count(key(q[i], q[j]))) chords.insert(key(q[i], q[j]));
  std::vector<std::vector<std::uint32_t>> node_tets(mesh.nodes.size());
  for (std::uint32_t t = 0; t < mesh.tets.size(); ++t)
    for (std::uint32_t v : mesh.tets[t]) node_tets[v].push_back(t);
  for (const Edge& e : chords) {
    const auto m = static_cast<std::uint32_t>(mesh.nodes.size());
    mesh.nodes.push_back(0.5 * (mesh.nodes[e.first] + mesh.nodes[e.second]));
    node_tets.emplace_back();
    std::vector<std::uint32_t> around;  // the tets holding both ends
    for (std::uint32_t t : node_tets[e.first]) {
      const Tet& q = mesh.tets[t];
      if (std::find(q.begin(), q.end(), e.second) != q.end()) around.push_back(t);
    }
    for (std::uint32_t t : around) {
      Tet a = mesh.tets[t], b = mesh.tets[t];
      std::replace(a.begin(), a.end(), e.second, m);  // keeps e.first: orientation as the parent
      std::replace(b.begin(), b.end(), e.first, m);   // keeps e.second
      mesh.tets[t] = a;
      const auto nt = static_cast<std::uint32_t>(mesh.tets.size());
      mesh.tets.push_back(b);
      auto& second = node_tets[e.second];
      second.erase(std::find(second.begin(), second.end(), t));
      for (std::uint32_t v : b)
        if (v != e.second && v != m) node_tets[v].push_back(nt);
      second.push_back(nt);
      node_tets[m].push_back(t);
      node_tets[m].push_back(nt);
    }
  }
  return chords.size();
}

}  // namespace

TetMesh mesh_cavity(const TriangleMesh& surface, const CavityMeshOptions& options) {
  // TetGen 1.5 can crash rather than stop on a self-intersecting surface: such input is refused first.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  if (const std::size_t crossing = count_self_intersections(surface, &pairs, 1); crossing > 0)
    throw SolverError(ErrorCode::VolumeMeshFailed, {},
                      fmt::format("the surface to fill intersects itself ({} crossing triangle pairs, the first {} and "
                                  "{}): it has no cavity to mesh",
                                  crossing, pairs.front().first, pairs.front().second),
                      "check the reconstruction with `contour4d evaluate OUTDIR --check`; keep the ends closed");
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(surface.positions.size());
  in.pointlist = new REAL[surface.positions.size() * 3];
  for (std::size_t v = 0; v < surface.positions.size(); ++v) {
    in.pointlist[3 * v] = surface.positions[v].x;
    in.pointlist[3 * v + 1] = surface.positions[v].y;
    in.pointlist[3 * v + 2] = surface.positions[v].z;
  }
  in.numberoffacets = static_cast<int>(surface.triangles.size());
  in.facetlist = new tetgenio::facet[surface.triangles.size()];
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    tetgenio::facet& f = in.facetlist[t];
    tetgenio::init(&f);
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&f.polygonlist[0]);
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) f.polygonlist[0].vertexlist[k] = static_cast<int>(surface.triangles[t][k]);
  }
  std::string switches = fmt::format("pYMzQq{}/{}", options.radius_edge, options.min_dihedral_deg);
  if (options.max_volume_mm3 > 0.0) switches += fmt::format("a{}", options.max_volume_mm3);
  try {
    tetrahedralize(switches.data(), &in, &out);
  } catch (int code) {
    throw SolverError(ErrorCode::VolumeMeshFailed, {}, "TetGen could not mesh the cavity: " + tetgen_reason(code),
                      "check the surface with `contour4d evaluate OUTDIR --check`");
  }
  TetMesh mesh;
  mesh.surface_nodes = surface.positions.size();
  if (out.numberofpoints < in.numberofpoints || out.numberofcorners != 4 || out.numberoftetrahedra <= 0)
    throw SolverError(ErrorCode::VolumeMeshFailed, {}, "TetGen returned no tetrahedra for the cavity");
  mesh.nodes.resize(static_cast<std::size_t>(out.numberofpoints));
  for (std::size_t v = 0; v < mesh.nodes.size(); ++v)
    mesh.nodes[v] = {out.pointlist[3 * v], out.pointlist[3 * v + 1], out.pointlist[3 * v + 2]};
  for (std::size_t v = 0; v < mesh.surface_nodes; ++v)
    if (mesh.nodes[v].x != surface.positions[v].x || mesh.nodes[v].y != surface.positions[v].y ||
        mesh.nodes[v].z != surface.positions[v].z)
      throw SolverError(ErrorCode::VolumeMeshFailed, {},
                        fmt::format("TetGen moved or renumbered surface vertex {}", v));
  mesh.tets.resize(static_cast<std::size_t>(out.numberoftetrahedra));
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    Tet q;
    for (int k = 0; k < 4; ++k)
      q[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(out.tetrahedronlist[4 * t + k]);
    if (tet_volume(mesh.nodes[q[0]], mesh.nodes[q[1]], mesh.nodes[q[2]], mesh.nodes[q[3]]) < 0.0) std::swap(q[2], q[3]);
    mesh.tets[t] = q;
  }
  split_chords(mesh, surface.triangles);
  mesh.boundary = surface.triangles;
  mesh.boundary_tet = boundary_tets(mesh);
  return mesh;
}

}  // namespace c4d
