#pragma once
//! \file ends.h
//! \brief The ends of a reconstructed structure (the caps beyond its end contours) and the flow faces made of
//! them: each chosen end becomes a flat face in its end plane, the same triangles in every frame, with its own id.
//!
//! An end is found on frame 0 alone, from the mesh and the stack normal: the contour vertices lie on the slice
//! planes, and a cap is a patch of triangles on one side of a plane whose border is made of edges lying in that
//! plane and which reaches no other slice plane (docs/export.md, "Faces"). The ends on the side whose end contours
//! are larger are the base (an LV's valve plane, the left heart's inflow and outflow tracts); the other side's are
//! the apex.

#include <cstdint>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/vec.h"

namespace c4d {

//! One end of frame 0's surface: a cap beyond an end contour.
struct SurfaceEnd {
  int side = 1;                          //!< +1: beyond along the stack normal, -1: against it
  bool base = false;                     //!< on the base side (the side with the larger end contours)
  double offset_mm = 0.0;                //!< the end plane: dot(stack normal, x) = offset (frame 0)
  double area_mm2 = 0.0;                 //!< the area enclosed by its border in the plane (holes taken off)
  Vec3 centroid;                         //!< of its border loops' vertices (frame 0)
  std::vector<std::uint32_t> triangles;  //!< the cap's triangles
  std::vector<std::uint32_t> border;     //!< vertices on its border (the end contours), sorted
  std::vector<std::uint32_t> inner;      //!< its other vertices, sorted
  int loops = 0;                         //!< border loops (2 for a ring cap: an outer contour and a hole)
  std::string name;                      //!< face name when opened ("base", "inlet", "outlet", "apex", ...)
};

//! The slices' normal made exact on the mesh: `guess` (report.json's stack_normal, rounded to 4 decimals) tilts
//! the contour vertices of a slice off one offset by up to ~0.005 mm; the planes fitted to the dense clusters of
//! offsets (the contours) give the normal back to rounding. Returns `guess` when no cluster is found.
Vec3 refine_normal(const TriangleMesh& mesh, const Vec3& guess);

//! Finds the ends of `mesh` (frame 0) for slices normal to `normal` (report.json's stack_normal), ordered base
//! side first, then by decreasing area; each gets its default face name: one base end "base", two "inlet" (the
//! larger) and "outlet", more "base1", "base2", ...; apex side "apex" or "apex1", ...
//! Empty when no end is found (no vertices on slice planes: not a contour4d reconstruction).
std::vector<SurfaceEnd> find_ends(const TriangleMesh& mesh, const Vec3& normal);

//! Which ends to open: "base" (default), "apex", "all", "none", or a comma list of 1-based end numbers in
//! find_ends' order ("1,3"). \throw InvalidInput (Usage) on anything else or a number out of range.
std::vector<int> choose_ends(const std::vector<SurfaceEnd>& ends, const std::string& which);

//! A mesh sequence whose triangles carry a face id: 0 the wall, k > 0 the k-th opened end.
struct FacedSequence {
  MeshSequence seq;                              //!< the frames with every opened end flat
  std::vector<std::uint8_t> face;                //!< per triangle
  std::vector<std::string> names;                //!< per face id; names[0] = "wall"
  std::vector<double> ring_moved_mm;             //!< per opened end: the largest move of a border vertex onto its plane
  std::vector<std::vector<std::uint32_t>> band;  //!< per opened end: the wall vertices that take up the border's
                                                 //!< moves (between the border and the next contour), sorted
  std::vector<double> band_moved_mm;             //!< per opened end: the largest move of a band vertex
  std::vector<std::vector<int>> not_flat_frames;  //!< per opened end: frames where it stays as reconstructed
  std::vector<double> plane_offset_mm;  //!< offset of each opened end's plane in each frame: [end · frames + frame]
};

//! Makes each end of `open` (indices into `ends`) a flat face in every frame: its border vertices are put on
//! the frame's end plane (normal `normal`, offset the mean of theirs), the wall between the border and the next
//! contour (the band) moved along the normal by the harmonic extension of those moves, and its inner vertices at
//! the uniform (Tutte) harmonic map of that border, a few folded triangles unfolded within the plane (a border
//! with pixel dents). One sparse factorisation per end for all frames. Other ends stay closed as they were, part
//! of the wall. `names` overrides the ends' default names in order. In a frame where the flat face would still
//! fold, or it or the band would cross the wall, the end and the band keep their reconstructed shape in that
//! frame, the end still its own face (not_flat_frames).
//! \throw InvalidInput (InvertedElement) when an end's flat face folds in every frame; InvalidInput (Usage)
//! for a repeated or empty name.
FacedSequence open_ends(const MeshSequence& seq, const Vec3& normal, const std::vector<SurfaceEnd>& ends,
                        const std::vector<int>& open, const std::vector<std::string>& names = {});

}  // namespace c4d
