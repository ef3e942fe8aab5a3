#pragma once
// Fixtures shared by the temporal and render tests: the synthetic beating shape and a small patch
// mesh (base mesh + displacement maps) built from it.
#include <cstddef>

#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/sequence.h"

namespace c4d::test {

//! The beating shape, the options its patch mesh was built with, and the patch mesh.
struct BeatingPatches {
  MeshSequence seq;      //!< synthetic_beating_mesh(subdivisions, frames)
  PatchOptions options;  //!< base_triangles and grid as asked, other fields default
  PatchMesh mesh;        //!< build_patch_mesh(seq, options)
};

//! The beating shape with `subdivisions` and `frames`, and its patch mesh of about `base_triangles`
//! base triangles with `grid` lattice steps per base edge.
inline BeatingPatches beating_patches(int subdivisions, std::size_t frames, std::size_t base_triangles, int grid) {
  BeatingPatches b;
  b.seq = synthetic_beating_mesh(subdivisions, frames);
  b.options.base_triangles = base_triangles;
  b.options.grid = grid;
  b.mesh = build_patch_mesh(b.seq, b.options);
  return b;
}

}  // namespace c4d::test
