// The cavity mesh moving with the wall: the wall displacement extended by Laplace's equation (P1 finite
// elements), the classic mesh-motion operator of ALE flow solvers (A. A. Johnson, T. E. Tezduyar, "Mesh update
// strategies in parallel finite element computations of flow problems with moving boundaries and interfaces",
// CMAME 119, 1994, whose Jacobian-based stiffening, each element's stiffness scaled by a volume ratio so that
// small elements near the wall move nearly rigidly, is the fallback). The operator is linear and time does not
// enter it, so the key frames are solved once with one factorisation and every output time combines them with
// the wall's own Catmull-Rom weights.
#include "contour4d/solver/cavity_motion.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "contour4d/core/errors.h"
#include "contour4d/core/sparse_solve.h"
#include "contour4d/solver/time_steps.h"

namespace c4d {
namespace {

constexpr double kStiffening = 2.0;  // Jacobian-based stiffening exponent χ of the fallback (Tezduyar's 0…2)

struct System {
  Eigen::SparseMatrix<double> inner;     // inner × inner, lower triangle
  Eigen::SparseMatrix<double> coupling;  // inner × surface
};

// The P1 Laplacian on the tets at positions `x`: element matrix k_e V ∇φ_i·∇φ_j with ∇φ_i = −n_i / (6V), n_i twice
// the outward area vector of the face opposite node i; k_e = 1 (harmonic) or (V̄ / V)^χ (stiffened).
System assemble(const TetMesh& mesh, const std::vector<Vec3>& x, Extension extension) {
  const std::size_t nb = mesh.surface_nodes, ni = mesh.nodes.size() - nb;
  double mean_volume = 0.0;
  for (const Tet& q : mesh.tets) mean_volume += std::abs(tet_volume(x[q[0]], x[q[1]], x[q[2]], x[q[3]]));
  mean_volume /= static_cast<double>(std::max<std::size_t>(mesh.tets.size(), 1));
  std::vector<Eigen::Triplet<double>> inner, coupling;
  for (const Tet& q : mesh.tets) {
    const Vec3 &a = x[q[0]], &b = x[q[1]], &c = x[q[2]], &d = x[q[3]];
    const Vec3 n[4] = {cross(c - b, d - b), cross(d - a, c - a), cross(b - a, d - a), cross(c - a, b - a)};
    // |V|: a tet inverted on the way (the stiffened chain runs on moved meshes) still adds a positive
    // semi-definite element, that of its mirror image, so the system stays definite.
    const double v = std::max(std::abs(tet_volume(a, b, c, d)), 1e-12 * mean_volume);
    const double k = extension == Extension::Stiffened ? std::pow(mean_volume / v, kStiffening) : 1.0;
    for (int i = 0; i < 4; ++i) {
      if (q[i] < nb) continue;
      const int row = static_cast<int>(q[i] - nb);
      for (int j = 0; j < 4; ++j) {
        const double kij = k * dot(n[i], n[j]) / (36.0 * v);
        if (q[j] < nb)
          coupling.emplace_back(row, static_cast<int>(q[j]), kij);
        else if (q[j] - nb <= q[i] - nb)
          inner.emplace_back(row, static_cast<int>(q[j] - nb), kij);
      }
    }
  }
  System s;
  s.inner.resize(static_cast<int>(ni), static_cast<int>(ni));
  s.inner.setFromTriplets(inner.begin(), inner.end());
  s.coupling.resize(static_cast<int>(ni), static_cast<int>(nb));
  s.coupling.setFromTriplets(coupling.begin(), coupling.end());
  return s;
}

// Solves A_II u_I = −A_IB u_B for the wall displacements `walls` (3 columns each), one factorisation.
std::vector<std::vector<Vec3>> solve(const System& s, const std::vector<std::vector<Vec3>>& walls) {
  const std::size_t nb = static_cast<std::size_t>(s.coupling.cols()), ni = static_cast<std::size_t>(s.inner.rows());
  SparseLdlt ldlt;
  if (!factor_lower(ldlt, s.inner))
    throw SolverError(ErrorCode::Internal, {}, "the mesh-motion system of the cavity is singular");
  Eigen::MatrixXd wall(static_cast<Eigen::Index>(nb), static_cast<Eigen::Index>(3 * walls.size()));
  for (std::size_t f = 0; f < walls.size(); ++f)
    for (std::size_t v = 0; v < nb; ++v) {
      const auto r = static_cast<Eigen::Index>(v), c = static_cast<Eigen::Index>(3 * f);
      wall(r, c) = walls[f][v].x;
      wall(r, c + 1) = walls[f][v].y;
      wall(r, c + 2) = walls[f][v].z;
    }
  const Eigen::MatrixXd rhs = -(s.coupling * wall);
  const Eigen::MatrixXd x = ldlt_solve(ldlt, rhs);
  std::vector<std::vector<Vec3>> out(walls.size(), std::vector<Vec3>(ni));
  for (std::size_t f = 0; f < walls.size(); ++f)
    for (std::size_t i = 0; i < ni; ++i) {
      const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(3 * f);
      out[f][i] = {x(r, c), x(r, c + 1), x(r, c + 2)};
    }
  return out;
}

// The inner displacement (from frame 0) of every key frame. Harmonic: one system on frame 0's mesh, all frames
// solved at once. Stiffened: an updated-Lagrangian pseudo-solid, frame after frame, each frame's wall increment
// extended on the mesh as it then is, the stiffness re-assembled there (tets squeezed so far grow stiffer); run
// from frame 0 forwards to the middle of the cycle and backwards over the wrap to it, so that both chains start
// from frame 0's mesh and only meet once.
std::vector<std::vector<Vec3>> extend(const TetMesh& mesh, const MeshSequence& surface, Extension extension) {
  const std::size_t nb = mesh.surface_nodes, ni = mesh.nodes.size() - nb, frames = surface.positions.size();
  if (ni == 0) return std::vector<std::vector<Vec3>>(frames);
  if (extension == Extension::Harmonic) {
    std::vector<std::vector<Vec3>> walls(frames, std::vector<Vec3>(nb));
    for (std::size_t f = 0; f < frames; ++f)
      for (std::size_t v = 0; v < nb; ++v) walls[f][v] = surface.positions[f][v] - surface.positions[0][v];
    return solve(assemble(mesh, mesh.nodes, extension), walls);
  }
  std::vector<std::vector<Vec3>> out(frames, std::vector<Vec3>(ni));
  const std::size_t middle = frames / 2;
  for (int direction : {1, -1}) {
    std::vector<Vec3> x = mesh.nodes;
    std::size_t prev = 0;
    const std::size_t count = direction > 0 ? middle : frames - 1 - middle;
    for (std::size_t k = 1; k <= count; ++k) {
      const std::size_t f = direction > 0 ? k : frames - k;
      std::vector<std::vector<Vec3>> step(1, std::vector<Vec3>(nb));
      for (std::size_t v = 0; v < nb; ++v) step[0][v] = surface.positions[f][v] - surface.positions[prev][v];
      const std::vector<Vec3> du = solve(assemble(mesh, x, extension), step)[0];
      for (std::size_t v = 0; v < nb; ++v) x[v] = surface.positions[f][v];
      for (std::size_t i = 0; i < ni; ++i) {
        x[nb + i] = x[nb + i] + du[i];
        out[f][i] = x[nb + i] - mesh.nodes[nb + i];
      }
      prev = f;
    }
  }
  return out;
}

// Runs body(i) for i in [0, count) on `threads` workers (0: all cores).
template <class Body>
void for_each_index(std::size_t count, int threads, const Body& body) {
  auto range_body = [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) body(i);
  };
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), range_body); });
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), range_body);
  }
}

// Each key frame's cavity untangled (its inner displacement updated); the nodes moved per frame.
std::vector<std::size_t> untangle_key_frames(const TetMesh& mesh, const MeshSequence& surface, CavityMotion& m,
                                             int threads) {
  const std::size_t nb = mesh.surface_nodes;
  std::vector<std::size_t> moved(surface.positions.size(), 0);
  for_each_index(surface.positions.size(), threads, [&](std::size_t f) {
    std::vector<Vec3>& inner = m.inner_displacement[f];
    std::vector<Vec3> x = surface.positions[f];
    x.resize(mesh.nodes.size());
    for (std::size_t i = 0; i < inner.size(); ++i) x[nb + i] = mesh.nodes[nb + i] + inner[i];
    moved[f] = untangle_tets(x, mesh.nodes, mesh.tets, nb, m.stars);
    for (std::size_t i = 0; i < inner.size(); ++i) inner[i] = x[nb + i] - mesh.nodes[nb + i];
  });
  return moved;
}

std::vector<TetQuality> measure_steps(const TetMesh& mesh, const MeshSequence& surface, const CavityMotion& motion,
                                      const std::vector<double>& times_s, int threads,
                                      std::vector<std::size_t>& untangled) {
  std::vector<TetQuality> steps(times_s.size());
  untangled.assign(times_s.size(), 0);
  for_each_index(times_s.size(), threads, [&](std::size_t i) {
    std::size_t moved = 0;
    steps[i] =
        measure_tets(cavity_nodes_at(mesh, surface, motion, step_weights(surface, times_s[i]), &moved), mesh.tets);
    untangled[i] = moved;
  });
  return steps;
}

// The first step with an inverted tet, or times_s.size().
std::size_t first_inverted_step(const std::vector<TetQuality>& steps) {
  for (std::size_t i = 0; i < steps.size(); ++i)
    if (steps[i].inverted > 0) return i;
  return steps.size();
}

}  // namespace

std::vector<Vec3> cavity_nodes_at(const TetMesh& mesh, const MeshSequence& surface, const CavityMotion& motion,
                                  const TimeWeights& w, std::size_t* untangled) {
  std::vector<Vec3> nodes = combine_frames(surface.positions, w);
  const std::vector<Vec3> inner = combine_frames(motion.inner_displacement, w);
  nodes.resize(mesh.nodes.size());
  for (std::size_t i = 0; i < inner.size(); ++i)
    nodes[mesh.surface_nodes + i] = mesh.nodes[mesh.surface_nodes + i] + inner[i];
  const std::size_t moved = untangle_tets(nodes, mesh.nodes, mesh.tets, mesh.surface_nodes, motion.stars);
  if (untangled) *untangled = moved;
  return nodes;
}

CavityMotion cavity_motion(const TetMesh& mesh, const MeshSequence& surface, const std::vector<double>& times_s,
                           const CavityMotionOptions& options) {
  CavityMotion m;
  m.frame0 = measure_tets(mesh.nodes, mesh.tets);
  m.stars = node_stars(mesh.nodes.size(), mesh.tets);
  std::string faults;
  for (Extension extension : {Extension::Harmonic, Extension::Stiffened}) {
    m.extension = extension;
    try {
      m.inner_displacement = extend(mesh, surface, extension);
      m.untangled_key_nodes = untangle_key_frames(mesh, surface, m, options.threads);
    } catch (const SolverError& e) {
      if (extension == Extension::Harmonic || e.code() != ErrorCode::InvertedElement) throw;
      throw SolverError(ErrorCode::InvertedElement, {},
                        "the moving cavity mesh inverts: " + m.harmonic_fault + "; " + e.what(),
                        "nothing was written; try a finer surface (reconstruct --edge) or fewer opened ends");
    }
    m.steps = measure_steps(mesh, surface, m, times_s, options.threads, m.untangled_step_nodes);
    const std::size_t bad = first_inverted_step(m.steps);
    if (bad == m.steps.size()) break;
    const Tet& worst = mesh.tets[m.steps[bad].first_inverted];
    const auto on_wall =
        std::count_if(worst.begin(), worst.end(), [&](std::uint32_t v) { return v < mesh.surface_nodes; });
    const std::string fault = fmt::format(
        "{} extension: {} tets inverted at t = {} s (step {}), the first tet {} ({} of its nodes on the wall, volume "
        "{:.3g} mm³)",
        extension == Extension::Harmonic ? "harmonic" : "stiffened", m.steps[bad].inverted, times_s[bad], bad,
        m.steps[bad].first_inverted, on_wall, m.steps[bad].min_volume_mm3);
    if (extension == Extension::Harmonic) {
      m.harmonic_fault = fault;
      continue;
    }
    throw SolverError(ErrorCode::InvertedElement, {},
                      "the moving cavity mesh inverts: " + m.harmonic_fault + "; " + fault,
                      "nothing was written; try a finer surface (reconstruct --edge) or fewer opened ends");
  }
  m.min_dihedral_deg = 180.0;
  m.max_aspect_ratio = 0.0;
  m.min_volume_mm3 = m.steps.empty() ? 0.0 : m.steps.front().min_volume_mm3;
  for (const TetQuality& q : m.steps) {
    m.min_dihedral_deg = std::min(m.min_dihedral_deg, q.min_dihedral_deg);
    m.max_aspect_ratio = std::max(m.max_aspect_ratio, q.max_aspect_ratio);
    m.min_volume_mm3 = std::min(m.min_volume_mm3, q.min_volume_mm3);
  }
  return m;
}

}  // namespace c4d
