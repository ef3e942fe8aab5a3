#pragma once
//! \file cavity_motion.h
//! \brief The cavity mesh moving with its wall: the wall's displacement extended into the volume by a harmonic
//! (or stiffened) map, one sparse factorisation for the whole cycle, every tet checked at every output time.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/tet_mesh.h"
#include "contour4d/metrics/tet_quality.h"
#include "contour4d/solver/tet_untangle.h"
#include "contour4d/temporal/interpolate.h"

namespace c4d {

//! How the wall's displacement is carried into the cavity.
enum class Extension {
  Harmonic,   //!< Laplace's equation, P1 finite elements: each node at a weighted mean of its neighbours
  Stiffened,  //!< the same with each tet's stiffness scaled by (mean volume / its volume)²: small tets move rigidly
};

//! What cavity_motion does (the command line's names in brackets).
struct CavityMotionOptions {
  int threads = 0;  //!< [--threads] worker threads; 0: all cores. The result does not depend on it
};

//! The cavity at every output time.
struct CavityMotion {
  Extension extension = Extension::Harmonic;          //!< the one used (Stiffened where Harmonic inverted a tet)
  std::string harmonic_fault;                         //!< why Harmonic was not used ("" when it was)
  std::vector<std::vector<Vec3>> inner_displacement;  //!< per key frame, per inner node (node − surface_nodes) (mm)
  std::vector<TetQuality> steps;                      //!< per output time
  std::vector<std::size_t> untangled_step_nodes;      //!< per output time: inner nodes moved by untangle_tets
  std::vector<std::size_t> untangled_key_nodes;       //!< per key frame: inner nodes moved by untangle_tets
  NodeStars stars;                                    //!< each node's tets, for the repairs
  TetQuality frame0;                                  //!< the mesh as made (frame 0)
  double min_dihedral_deg = 180.0;                    //!< over every step
  double max_aspect_ratio = 0.0;                      //!< over every step
  double min_volume_mm3 = 0.0;                        //!< the smallest tet volume over every step
};

//! Moves `mesh` (made on frame 0 of `surface`, whose vertices are its first nodes) with the surface through the
//! output times `times_s` (s after frame 0; time_steps.h): the surface nodes at the periodic Catmull-Rom position
//! (step_weights), the inner nodes at frame 0's position plus the extension of the wall displacement. The
//! extension is linear, so it is solved once per key frame (one factorisation, one solve with three columns
//! per frame). Where the wall's vertices slide along it faster than a thin tet at the wall can follow, a tet may
//! invert: each key frame's inner nodes are then untangled (untangle_tets, against frame 0's shapes), and the
//! key frames are combined with the wall's own weights; a step whose combination still inverts a tet is
//! untangled locally in turn (cavity_nodes_at). Key frames and output times run in parallel; each writes its own
//! slot.
//! \throw SolverError (InvertedElement) naming the time (s), the tet and the extensions tried when a tet's
//! signed volume is <= 0 at some output time with both extensions.
CavityMotion cavity_motion(const TetMesh& mesh, const MeshSequence& surface, const std::vector<double>& times_s,
                           const CavityMotionOptions& options = {});

//! The node positions at `w` (a step_weights result): the surface combined from `surface`, the inner nodes
//! from frame 0 plus the combined inner displacements of `motion`; where a tet is then inverted or flat, the
//! inner nodes around it are untangled (untangle_tets, a local repair), and `untangled` (when given) gets how many
//! nodes moved.
std::vector<Vec3> cavity_nodes_at(const TetMesh& mesh, const MeshSequence& surface, const CavityMotion& motion,
                                  const TimeWeights& w, std::size_t* untangled = nullptr);

}  // namespace c4d
