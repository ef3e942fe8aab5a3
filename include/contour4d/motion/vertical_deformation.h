#pragma once
//! \file vertical_deformation.h
//! \brief 2D contour topology changes between two frames (Lim et al. 2014, "Handling 2D Contour
//! Topological Changes": "Determining Vertical Motion", "Ridge Detection" (Fig. 8), "Applying
//! Vertical Motion" (eq. 10, Table 1)).
//!
//! When a slice's contour count changes between frames t and t+1 (a split or a merge), the mesh of
//! frame t is first pushed along the stack normal around the saddle ("ridge") so that its section
//! by that slice already has the contour count of frame t+1; the standard deformation then follows.
//! Three steps, each a free function: the direction (vertical_motion_direction), the ridge
//! (detect_ridge), the sine displacement (make_vertical_field + apply_vertical_deformation).
//! Conventions: "above" means a larger Slice::offset along Sequence::normal, "up" is +normal; all
//! lengths are mm in the sequence's world space. docs/algorithms/vertical_deformation.md explains
//! the choices where the paper is vague.

#include <array>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! Direction of the induced vertical motion (along Sequence::normal).
enum class VerticalDirection { None, Up, Down };

//! What happened to a slice's contours between the two frames.
enum class ContourEvent { None, Split, Merge, Appear, Vanish };

//! How the direction of the vertical motion is decided.
enum class MotionRule {
  Auto,        //!< counts of the neighbouring slices when they decide, else the paper's similarity
  Similarity,  //!< the paper only: eq. 6 similarity of the incident slice with its neighbours in frame t+1
  Counts,      //!< the neighbour that carries, in frame t, the incident slice's count of frame t+1
};

//! How the ridge path is traced on the mesh.
enum class RidgePath {
  Greedy,    //!< the paper: always step to the neighbour closest to the end (shortest path when stuck)
  Shortest,  //!< Dijkstra over mesh edges (an edge-geodesic)
};

//! Options of the three steps. Defaults follow the paper where it gives a value.
struct VerticalDeformationOptions {
  MotionRule rule = MotionRule::Auto;  //!< see MotionRule
  double tie_tolerance = 1e-3;         //!< Similarity/Auto: score differences below this are a tie (then counts)
  double band = 0.10;                  //!< middle band: |dB − dC| ≤ band × max(dB, dC) (paper: 10 %)
  RidgePath path = RidgePath::Greedy;  //!< see RidgePath
  double slab_margin = 0.25;           //!< ridge path stays within the incident/complement slab ± this × their gap
  std::array<double, 6> r_upward{0.2, 0.4, 0.7, 1.2, 0.5, 0.2};          //!< Table 1, slices 1 (top) .. 6
  std::array<double, 6> r_downward{-0.2, -0.5, -1.2, -0.7, -0.4, -0.2};  //!< Table 1, slices 1 (top) .. 6
  double delta_scale = 1.0;  //!< δ = this × |offset(incident) − offset(complement)| (R = 1 moves by one gap)
  double taper = 1.0;        //!< beyond slices 1 and 6, R falls linearly to 0 over this × gap (0: the paper's cut)
};

//! The vertical motion needed on one slice between frames `frame` and `next_frame`.
struct VerticalMotion {
  VerticalDirection direction = VerticalDirection::None;  //!< None when no split/merge, or undecidable
  ContourEvent event = ContourEvent::None;                //!< what the incident slice's contours do
  int frame = 0, next_frame = 0;                          //!< frame indices (t, t+1)
  int incident_slice = -1;                                //!< slice id whose contour count changes
  int complement_slice = -1;       //!< below(incident) when Up, above(incident) when Down; -1 when None
  int contours_before = 0;         //!< contours of the incident slice in `frame`
  int contours_after = 0;          //!< contours of the incident slice in `next_frame`
  double similarity_below = 0.0;   //!< eq. 6: incident slice at t against the slice below it at t+1
  double similarity_above = 0.0;   //!< eq. 6: incident slice at t against the slice above it at t+1
  bool decided_by_counts = false;  //!< true when the count rule, not the similarity, gave the direction
};

//! Direction of the vertical motion on slice `slice_id` between `frame` and `next_frame`, by
//! options.rule: the paper's heuristic similarity(S_t^I, below_{t+1}) < similarity(S_t^I, above_{t+1})
//! ⇒ Up, > ⇒ Down (eq. 6), and/or the count rule (the complement is the neighbour that already has,
//! in `frame`, the incident slice's count of `next_frame`). Both scores are filled in either case.
//! Appear/Vanish (0 ↔ n contours) are reported with direction None.
//! \throw InvalidInput when a frame index is out of range.
VerticalMotion vertical_motion_direction(const Sequence& seq, int frame, int next_frame, int slice_id,
                                         const VerticalDeformationOptions& options = {});

//! vertical_motion_direction for every slice id whose contour count differs between the frames,
//! by increasing offset. \throw InvalidInput when a frame index is out of range.
std::vector<VerticalMotion> vertical_motions(const Sequence& seq, int frame, int next_frame,
                                             const VerticalDeformationOptions& options = {});

//! The two end points of the ridge on contour A (Fig. 8A).
struct RidgeEnds {
  bool found = false;                //!< false when fewer than two middle bands exist
  std::array<Vec3, 2> points{};      //!< end points (points of A, world mm)
  std::array<int, 2> index{-1, -1};  //!< their indices in A
  std::vector<int> band_sizes;       //!< sizes of all middle bands, largest first
};

//! Fig. 8A: projects A, B, C on `plane`; the middle band holds the points of A whose 2D distances to
//! B and C differ by at most options.band × the larger; of the two largest contiguous bands, the
//! point with the smallest difference in each. Ties go to the lower index.
RidgeEnds ridge_end_points(const std::vector<Vec3>& A, const std::vector<Vec3>& B, const std::vector<Vec3>& C,
                           const Plane& plane, const VerticalDeformationOptions& options = {});

//! A ridge: a path of mesh edges (Fig. 8B).
struct Ridge {
  bool found = false;                   //!< false when no end points or no path
  RidgeEnds ends;                       //!< the end points on A
  std::vector<std::uint32_t> vertices;  //!< mesh vertex ids, start to end
  std::vector<Vec3> points;             //!< their positions (mm)
  bool used_shortest_path = false;      //!< Greedy got stuck and Dijkstra finished the path
};

//! Path on `mesh` from vertex `from` to vertex `to`: Greedy (paper) or Shortest, over the vertices
//! whose height dot(p, normal) lies in [h_min, h_max] (`from` and `to` always allowed). Empty when
//! none exists. `used_shortest` (optional) tells whether Dijkstra was needed.
std::vector<std::uint32_t> mesh_path(const TriangleMesh& mesh, std::uint32_t from, std::uint32_t to, Vec3 normal,
                                     double h_min, double h_max, RidgePath path, bool* used_shortest = nullptr);

//! Fig. 8: end points from A (the lone contour of the incident/complement pair) and B, C (the two
//! contours of the other slice of the pair), then the path between the mesh vertices nearest to
//! them, kept within the slab between the planes of A and of B, C (± options.slab_margin × gap).
//! \pre A, B, C lie on planes normal to `normal`.
Ridge detect_ridge(const TriangleMesh& mesh, const std::vector<Vec3>& A, const std::vector<Vec3>& B,
                   const std::vector<Vec3>& C, Vec3 normal, const VerticalDeformationOptions& options = {});

//! Eq. 10 made ready to apply: everything the displacement of a point depends on.
struct VerticalField {
  Vec3 normal{0, 0, 1};             //!< unit stack normal (displacement direction for R > 0)
  Vec3 u{1, 0, 0}, v{0, 1, 0};      //!< in-plane axes for the 2D distances
  std::array<double, 6> heights{};  //!< offsets of slices 1 (top) .. 6 along normal (mm), decreasing
  std::array<double, 6> r{};        //!< R of each of those slices (Table 1)
  double delta = 0.0;               //!< δ (mm)
  double lambda = 0.0;              //!< λ: furthest 2D distance between the ridge and the incident slice (mm)
  double taper = 0.0;               //!< distance beyond slices 1 and 6 over which R falls to 0 (mm)
  std::vector<Vec2> ridge;          //!< ridge projected on (u, v) (mm)
};

//! Builds the field for `motion` (direction Up or Down): slice heights from the sequence (missing
//! neighbours extrapolated at the incident/complement gap), R from Table 1, δ, λ from
//! `incident_points` (the points of the incident slice's contours) and the ridge.
//! \throw InvalidInput when motion.direction is None, a slice id is unknown or the ridge is empty.
VerticalField make_vertical_field(const Sequence& seq, const VerticalMotion& motion, const std::vector<Vec3>& ridge,
                                  const std::vector<Vec3>& incident_points,
                                  const VerticalDeformationOptions& options = {});

//! Eq. 10 at point p: VD = δ R(h)/2 [sin(π (2D + λ)/(2λ)) + 1] for D < λ, else 0; R(h) linear in
//! height between the slices (tapered beyond slices 1 and 6). Signed, along field.normal (mm).
double vertical_displacement(const VerticalField& field, Vec3 p);

//! Moves every position by vertical_displacement(field, p) × field.normal.
void apply_vertical_deformation(std::vector<Vec3>& positions, const VerticalField& field);

}  // namespace c4d
