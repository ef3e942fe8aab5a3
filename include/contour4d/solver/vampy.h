#pragma once
//! \file vampy.h
//! \brief The hand-off to VaMPy / OasisMove (moving-domain FEniCS): the wall as an open surface at every step.
//!
//! FOLDER/model.vtp              the wall at t = 0, the opened ends left as holes (VaMPy finds its inlets and
//!                               outlets at the holes and adds its flow extensions there)
//! FOLDER/model_moved_NN.vtp     the same triangles at step NN (NN = 00 … steps, zero-padded to a common width)
//! Lengths in `length_scale` units of mm (VaMPy's surfaces are in mm: 1).

#include <string>

#include "contour4d/io/output_dir.h"
#include "contour4d/solver/handoff.h"

namespace c4d {

//! Writes the VaMPy surfaces of `h` into `out`/`folder`.
void write_vampy(const OutputDir& out, const std::string& folder, const Handoff& h, double length_scale = 1.0);

}  // namespace c4d
