#pragma once
//! \file phantom.h
//! \brief Analytic test shapes with exact plane sections and a fine ground-truth mesh per frame
//! (Lim et al., "Comparison with Idealized Model"; docs/phantoms.md).
//!
//! Every contour vertex lies exactly on the analytic surface, and the truth mesh of a frame
//! contains every contour of that frame as a chain of its own edges, so the conformity of the
//! truth against its own contours is zero up to rounding.

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! How to slice and mesh a phantom.
struct PhantomOptions {
  double spacing = 5.0;  //!< distance between slice planes (mm), > 0
  double offset = std::numeric_limits<double>::
      quiet_NaN();  //!< one slice plane lies at this height on the slice axis (mm, phantom frame); NaN: the phantom's default
  int frames = 0;           //!< frames of a cyclic phantom; 0: the phantom's default (ignored by single-frame phantoms)
  bool oblique = false;     //!< move contours and truth by oblique_rotation() and oblique_translation()
  double truth_edge = 0.5;  //!< target edge length of the truth mesh (mm), in [0.05, 10]
};

//! A phantom: validated contours, the true surface per frame and its volume.
struct Phantom {
  std::string name;                     //!< e.g. "left-heart"
  std::string description;              //!< one line
  Sequence contours;                    //!< sections by the slice planes, label "lv" (left-heart*) or the phantom name
  std::vector<TriangleMesh> truth;      //!< one closed, outward-oriented 2-manifold mesh per frame (mm)
  std::vector<double> true_volume_mm3;  //!< enclosed volume per frame: analytic where known, else of the truth mesh
  double slab_min = 0.0;  //!< offset (mm, along contours.normal) of the first slice plane that cuts any frame
  double slab_max = 0.0;  //!< offset of the last such plane
  std::vector<std::vector<double>>
      shape_parameters;  //!< per frame, the analytic parameters (docs/phantoms.md lists them)
  bool oblique = false;  //!< whether the oblique motion was applied to contours and truth
};

//! Names accepted by make_phantom, in a fixed order.
std::vector<std::string> phantom_names();

//! One-line description of a phantom. \throw InvalidInput (ErrorCode::Usage) for an unknown name.
std::string phantom_description(const std::string& name);

//! Builds a phantom. Fast (well under a second at the defaults).
//! \throw InvalidInput (ErrorCode::Usage) for an unknown name or out-of-range options; the
//! message lists the valid names.
Phantom make_phantom(const std::string& name, const PhantomOptions& options = {});

//! Approximate signed distance (mm; implicit value over gradient norm, exact to first order near
//! the surface; negative inside) of world point p from the analytic surface of frame `frame`.
//! Flat caps (left-heart, bifurcation) are included.
double analytic_distance(const Phantom& phantom, int frame, Vec3 p);

//! The fixed rigid motion applied by PhantomOptions::oblique: world = R * local + t, R a rotation
//! of 30° about (1, 2, 3)/√14, t = (12, −7, 33) mm. Rows of R.
std::array<Vec3, 3> oblique_rotation();
//! Translation part of the oblique motion (mm).
Vec3 oblique_translation();

}  // namespace c4d
