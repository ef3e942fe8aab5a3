#pragma once
//! \file surface_plan.h
//! \brief One frame's surface with its counts fixed, to build every frame on the same mesh (Miara et al.
//! §III.D: one base mesh for all frames; Lim et al. 2014's tiling between connected contours).
//!
//! A plan holds what the one-frame surface decides from the geometry of the frame it was made on: the
//! canonical in-plane frame, how many points each contour gets, which contours are joined, the rows of each
//! band, each cap's pattern and the triangles. Another frame whose contours keep the same topology (the same
//! slices, contours per slice and links) is built on the plan (reconstruct.h, reconstruct_frame_on_plan):
//! each contour sampled at the plan's count by equal arc length from the start that best matches the plan
//! frame's contour, the rows interpolated along the same spanning edges, cap points carried by mean-value
//! coordinates; then the same fairing and filling as any one-frame surface. The result is that frame's own
//! surface, with the plan's vertices and triangles.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/vec.h"
#include "contour4d/surface/tiling.h"

namespace c4d {

//! One contour of the plan's frame.
struct PlanNode {
  int slice = 0;                //!< index into the plan's slices
  int depth = 0;                //!< nesting depth in its slice (odd: a hole)
  Vec2 centroid;                //!< centroid of its points (local frame, mm), to match other frames' contours
  std::vector<Vec2> reference;  //!< the contour at the plan's count, equal arc length from its canonical start
};

//! One cap of the plan: its interior points as mean-value coordinates over the loops' points.
struct PlanCap {
  std::size_t loop_points = 0;               //!< points on the cap's loops (its first points)
  std::vector<std::vector<double>> weights;  //!< per interior point: one weight per loop point, summing to 1
  std::vector<double> height;                //!< per interior point: lift as a share of the cap's height
  std::vector<Triangle> triangles;           //!< the cap's triangles (its own point indices)
};

//! A vertex of the plan's final mesh off the contours: where it lies on the faired mesh.
struct PlanPoint {
  std::uint32_t triangle = 0;       //!< index into SurfacePlan::triangles
  std::array<double, 3> weights{};  //!< barycentric coordinates in that triangle
};

//! What the one-frame surface of one frame decided, to build others on the same mesh.
struct SurfacePlan {
  std::string unusable;                                 //!< why other frames cannot be built on it; empty: usable
  Vec2 centre, axis{1, 0};                              //!< the canonical in-plane frame, kept for every frame
  std::vector<int> slice_ids;                           //!< the structure's slices, by increasing offset
  std::vector<PlanNode> nodes;                          //!< the contours, in the surface's order
  std::vector<std::vector<std::pair<int, int>>> links;  //!< per slice pair (lower index): linked node pairs
  std::vector<RowPlan> bands;                           //!< per band, in tiling order
  std::vector<PlanCap> caps;                            //!< per cap, in capping order
  std::vector<Triangle> triangles;                      //!< the tiled, capped surface, faired
  std::size_t vertices = 0;                             //!< its vertex count
  std::size_t contour_vertices = 0;                     //!< its vertices [0, this) lie on the contours
  std::vector<PlanPoint> embedding;                     //!< the final mesh's other vertices on the faired mesh
  std::vector<Triangle> final_triangles;                //!< the final mesh (remeshed, repaired): contour vertices
                                                        //!< first, then one per `embedding` entry
};

//! `count` points at equal arc length along closed `polygon` (≥ 2 distinct points), the first at arc-length
//! fraction `start` (0 ≤ start < 1) from its first vertex.
std::vector<Vec2> resample_count(const std::vector<Vec2>& polygon, std::size_t count, double start = 0.0);

//! `polygon` resampled at reference.size() equal arc-length steps from the start that best matches
//! `reference` (the largest correlation of the two about their centroids; same orientation assumed).
std::vector<Vec2> aligned_samples(const std::vector<Vec2>& polygon, const std::vector<Vec2>& reference);

//! Mean-value coordinates of `x` over the points of `loops` (an outer loop counter-clockwise and its holes
//! clockwise; Hormann & Floater 2006): one weight per point, loops in order, summing to 1. x inside the region.
std::vector<double> mean_value_weights(Vec2 x, const std::vector<std::vector<Vec2>>& loops);

//! The mean of `points` (0, 0 when empty): a contour's centroid for matching it across frames.
Vec2 mean_point(const std::vector<Vec2>& points);

//! Barycentric coordinates of p projected onto the plane of triangle (a, b, c); (1, 0, 0) when degenerate.
std::array<double, 3> barycentric(Vec3 p, Vec3 a, Vec3 b, Vec3 c);

}  // namespace c4d
