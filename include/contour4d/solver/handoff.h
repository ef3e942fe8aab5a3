#pragma once
//! \file handoff.h
//! \brief What every flow-solver writer is given: the surface with its faces, the cavity mesh, its motion and
//! the output times; and the positions at each output time.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "contour4d/core/tet_mesh.h"
#include "contour4d/solver/cavity_motion.h"
#include "contour4d/solver/ends.h"
#include "contour4d/solver/time_steps.h"

namespace c4d {

//! The hand-off to a flow solver (mm, key-frame times in ms, output times in s).
struct Handoff {
  FacedSequence surface;  //!< the key frames, flat faces at the opened ends, face id per triangle
  TetMesh cavity;         //!< frame 0's cavity; its first nodes are the surface's vertices
  CavityMotion motion;    //!< the cavity at every output time
  TimeSteps steps;        //!< the output times
};

//! The surface's vertex positions at output step `step` (mm): surface.seq at steps.times_s[step].
std::vector<Vec3> surface_at(const Handoff& h, std::size_t step);

//! The weights of every output step (step_weights of each time), for writers that go vertex by vertex.
std::vector<TimeWeights> all_step_weights(const Handoff& h);

//! The vertices used by the triangles of face `face` (sorted) and those triangles (indices into the surface).
struct FacePart {
  std::vector<std::uint32_t> vertices;
  std::vector<std::uint32_t> triangles;
};
FacePart face_part(const Handoff& h, int face);

//! The unit-conversion factor from mm for a length-unit name: "m" 0.001, "cm" 0.1, "mm" 1.
//! \throw InvalidInput (Usage) for another name.
double length_scale(const std::string& unit);

//! Decimals that write a length in `scale` units (length_scale) to 1e-9 mm: 9 for mm, 12 for m.
int length_decimals(double scale);

}  // namespace c4d
