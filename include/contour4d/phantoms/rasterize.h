#pragma once
//! \file rasterize.h
//! \brief A phantom as a label image (a point-sampled mask), for the round trip mask → contours →
//! 4D mesh and for comparisons with marching cubes (docs/phantoms.md, docs/images.md).

#include "contour4d/core/vec.h"
#include "contour4d/io/images.h"
#include "contour4d/phantoms/phantom.h"

namespace c4d {

//! How a phantom is sampled on a voxel grid.
struct RasterizeOptions {
  double pixel_x = 1.0;  //!< in-plane voxel size along voxel axis i (mm), > 0
  double pixel_y = 1.0;  //!< in-plane voxel size along voxel axis j (mm), > 0
  double margin = 3.0;   //!< empty border around the union of the frames' truth meshes (mm), >= 0
  Vec2 shift_px{0.37,
                -0.21};  //!< in-plane shift of the grid (fractions of a voxel) so the shape is not symmetric about it
  int label = 1;         //!< value of the voxels inside, 1..32767
};

//! Samples every frame of `phantom` at the voxel centres: a voxel takes `label` when its centre lies
//! inside the analytic surface (analytic_distance < 0), else 0. The slices (voxel axis k) are the
//! phantom's slice planes, so voxel index k is the contours' slice id and the image's exact sections
//! are the phantom's contours. Axes i, j span the slice plane (for --oblique phantoms, the oblique
//! rotation of two local axes, so the direction matrix is oblique); i × j = k, which points towards
//! increasing slice id. Coordinates: the phantom's world frame (mm), written as LPS.
//! \pre the phantom has at least two slice planes (contours on two slice ids)
//! \throw InvalidInput (Usage) for out-of-range options or a phantom with one slice plane.
std::vector<LabelVolume> rasterize_phantom(const Phantom& phantom, const RasterizeOptions& options = {});

}  // namespace c4d
