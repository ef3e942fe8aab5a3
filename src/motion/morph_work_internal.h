#pragma once
// The 4D morph's shared state and steps (Lim et al. 2014, "4D Morphing of the Heart Model"; Miara et al.
// §III.E). morph.cpp drives them frame after frame; the state the steps share is plain data, as the
// one-frame surface's (surface/reconstruct.cpp, FrameWork): MorphWork for the whole sequence (built once
// from frame 0's mesh), FrameWork for the frame being morphed, MorphTry for what changes between its tries.
//   morph_match.cpp  chains ↔ the frame's contours, topology events, held chains, vertical pre-deformation
//   morph_relax.cpp  the tangential relaxation (step 3)
//   morph_snap.cpp   vertices onto the frame's contours (steps 3b, 3b', 3c)
//   morph_fit.cpp    the guarded contour fit (step 5)

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "contour4d/core/mesh.h"
#include "contour4d/core/sparse_solve.h"
#include "contour4d/core/stack.h"
#include "contour4d/metrics/surface_projector.h"
#include "contour4d/motion/chains.h"
#include "contour4d/motion/morph.h"
#include "morph_internal.h"

namespace c4d::detail {

using SparseMatrix = Eigen::SparseMatrix<double>;

// A frame's triangles should keep every angle above this (degrees): below it a frame is tried again, and the
// contour fit repairs the angles it takes below it.
constexpr double kRetryMinAngleDeg = 25;

// A frame-0 chain vertex and its point on the matched contour of the frame (Fig. 7).
struct ChainTarget {
  std::uint32_t vertex;
  Vec3 position;
  int line;   // >= 0: slides along this matched contour (index into FrameWork::lines)
  int slice;  // slice id of the chain
};

// Frame 0's bands between the slices that carry contour chains.
struct Bands {
  std::vector<double> heights;        // slice heights along the stack normal, ascending
  std::vector<int> slice_ids;         // the slices at those heights
  std::vector<double> areas;          // band_areas of frame 0's mesh
  std::map<int, double> perimeters;   // slice_perimeters of frame 0
  std::map<int, std::size_t> counts;  // contours per slice id of frame 0
};

// The mesh as the relaxation sweeps read it: the vertices in breadth-first order (position k is vertex
// order[k]), so that neighbours lie near each other in memory, with their rings and the edges opposite
// them in their triangles (in the triangles' outward order), by position.
struct RelaxLayout {
  std::vector<std::uint32_t> order;  // position → vertex
  std::vector<std::size_t> ring_start;
  std::vector<std::uint32_t> ring_index;
  std::vector<std::size_t> opp_start;  // opposite edges: pairs in opp_index
  std::vector<std::uint32_t> opp_index;
  int lanes = 1;                         // vertices per sweep step (MorphSteps::sweep_lanes)
  std::vector<std::size_t> free_k;       // per block of positions: those with a ring, grouped by ring shape
  std::vector<std::size_t> block_start;  // block b's are free_k[block_start[b] .. block_start[b + 1])
};

// Projection of all vertices onto one frame's surface; each vertex remembers the triangle it last
// landed on and starts its next search there (the vertices move little between passes). The hint
// only narrows the search, so the result does not depend on the thread count.
// The vertices are visited in `order` (when given, a permutation of them): consecutive queries then
// fall on nearby parts of the tree. Each vertex's answer depends on its own query and hint only.
struct Projector {
  const SurfaceProjector* surface = nullptr;
  mutable std::vector<std::int32_t> hints;
  const std::vector<std::uint32_t>* order = nullptr;
  std::vector<Vec3> project(const std::vector<Vec3>& x, std::vector<Vec3>* normals = nullptr) const;
};

// The whole sequence's state: frame 0's mesh and adjacency, its chains and bands, the projection's
// factorisation, the mesh carried from frame to frame.
struct MorphWork {
  MorphWork(const Sequence& s, const TriangleMesh& f0, const MorphOptions& o, const MorphSteps& st, MorphReport& r)
      : seq(s), frame0(f0), opt(o), steps(st), rep(r) {}
  const Sequence& seq;
  const TriangleMesh& frame0;
  const MorphOptions& opt;
  const MorphSteps& steps;
  MorphReport& rep;
  bool project = false;                              // MorphMethod::RbfProject
  std::size_t nv = 0;                                // vertices
  std::vector<std::vector<std::uint32_t>> nb;        // each vertex's ring
  std::vector<std::vector<std::uint32_t>> incident;  // each vertex's triangles
  std::vector<std::size_t> ring_start;               // the rings in CSR form
  std::vector<std::uint32_t> ring_index;
  RelaxLayout layout;
  std::vector<Chain> chains;  // frame 0's contour chains
  Bands bands;                // frame 0's, between the chains' slices
  double median_edge = 0;     // frame 0's (mm)
  double slide_spacing = 0;   // MorphSteps::slide_spacing in mm (RbfProject; else 0)
  std::map<int, int> counts;  // contours per slice id of the frame before (topology events)
  SparseMatrix LtL;           // LᵀL of the uniform Laplacian (RbfProject)
  SparseLdlt solver;          // I + αLᵀL (project_onto_surface), factored at the first frame
  bool factored = false;
  std::vector<Vec3> carry;  // the previous frame's mesh, before its contour fit
};

// The frame being morphed.
struct FrameWork {
  FrameWork(int frame, MorphFrameReport& report, std::vector<Vec3> start) : t(frame), fr(report), x(std::move(start)) {}
  int t;                                 // the frame
  MorphFrameReport& fr;                  // its report
  std::vector<Vec3> x;                   // the mesh, from the previous frame's
  std::vector<ChainTarget> matched;      // the matched chains' vertices
  std::vector<std::vector<Vec3>> lines;  // the matched contours of frame t
  std::set<int> unmatched;  // slices whose contours changed (or change into the next frame), or left a chain alone
  std::set<int> held;       // slices whose chains do not slide in the relaxation
  std::vector<std::int32_t> slide_line;  // per vertex: the contour (line) it slides along, -1: none
  std::vector<std::int32_t> slide_hint;  // per vertex: the segment of it last found
  std::vector<char> sliding;             // slides through the relaxation (else only snapped after it, if harmless)
  std::vector<char> on_contour;          // is on its contour (moves along it)
  // RbfProject:
  std::unique_ptr<SurfaceProjector> surface;  // frame t's own surface
  Projector proj;
  std::vector<Vec3> normals;      // the surface's normals at x, from the last projection
  double curv_dev = 0;            // MorphSteps::saddle_curvature in mm
  std::vector<char> saddle_zone;  // per vertex: in a band beside a slice whose contours split or merged
};

// What changes between the tries of a frame (relax_with_retries): the first try's values, then a retry's.
struct MorphTry {
  int sweep_factor = 1;               // the relaxation runs this × its rounds (8 in the first retry, then doubling)
  double relax_settled = 0.01;        // a relaxation round stops once no vertex moved more than this × the median edge
                                      // in its last sweep (0 in a retry: every sweep). Cycle phantoms 20–25 % faster
  bool saddle_weights = true;         // MorphSteps::saddle_curvature (not in a retry)
  bool chains_onto_contours = true;   // step 3b (not in a retry: no chain vertex is put on its contour)
  int plane_snap_good_loss = -1;      // plane snap: how many of the ring's angles in 40–80° it may lose (-1: any)
  std::size_t corner_candidates = 3;  // step 3c: nearest vertices on the contour tried per corner
  bool corner_any_vertex = false;     // step 3c: any vertex near the corner may take it, not only those on the
                                      // contour (a retry, whose chain vertices stay off their contours)
};

// Closest point to p on the contour vertex i slides along (FrameWork::slide_line), from its last segment.
inline Vec3 slide(FrameWork& f, std::size_t i, Vec3 p) {
  return closest_on_loop(f.lines[static_cast<std::size_t>(f.slide_line[i])], p, f.slide_hint[i]);
}

// morph_match.cpp
std::vector<Vec2> flatten(const Plane& pl, const std::vector<Vec3>& pts);
const Slice* find_slice(const Frame& f, int id);
void build_bands(MorphWork& w);
void vertical_predeformation(const MorphWork& w, FrameWork& f);
void match_chains(MorphWork& w, FrameWork& f);
void hold_chains(const MorphWork& w, FrameWork& f, const TriangleMesh& surface);
void mark_saddle_zone(const MorphWork& w, FrameWork& f);
// morph_relax.cpp
void build_relax_layout(MorphWork& w);
void relax(const MorphWork& w, FrameWork& f, const MorphTry& tr);
void relax_round(const MorphWork& w, FrameWork& f, const MorphTry& tr);
// morph_snap.cpp
void put_sliding_on_contours(FrameWork& f);
void snap_chains_to_contours(const MorphWork& w, FrameWork& f);
void snap_to_planes(const MorphWork& w, FrameWork& f, const MorphTry& tr);
std::vector<char> snap_contour_corners(const MorphWork& w, FrameWork& f, const MorphTry& tr);
// morph_fit.cpp
void fit_frame(const MorphWork& w, std::size_t t, const std::vector<Vec3>& before, std::vector<Vec3>& out);

}  // namespace c4d::detail
