#pragma once
//! \file displacement_map.h
//! \brief Coarse base mesh + per-triangle displacement maps for tessellated playback (Miara et al.
//! §III.D–E: "a single compound base mesh and N displacement maps"; Vlachos et al. 2001, curved PN
//! triangles).
//!
//! The base mesh is the frame-0 mesh simplified by meshopt_simplify (its vertices are fine vertices,
//! so they move with the fine mesh). Each base triangle is a cubic PN patch built from its corners
//! and their normals; per frame, a scalar displacement along the patch's (linearly interpolated,
//! normalised) normal is stored on a barycentric lattice of `grid` steps per edge. The tessellated,
//! displaced patches approximate the fine surface of every frame. Everything is in the input space
//! (mm). The GPU shaders (render/patch_renderer.h) and patch_point evaluate the same formulas.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of build_patch_mesh.
struct PatchOptions {
  std::size_t base_triangles = 2000;  //!< target triangle count of the base mesh
  int grid = 8;                       //!< lattice steps per base edge: (g+1)(g+2)/2 samples per triangle
  double search_mm = 4.0;             //!< how far along the normal a sample looks (mm; at least the mean base edge)
};

//! A base mesh with per-frame corner data and displacement maps: plain, GPU-ready data.
struct PatchMesh {
  std::vector<Triangle> triangles;           //!< base triangles (ids into the base vertices)
  std::vector<std::uint32_t> fine_ids;       //!< fine vertex id of each base vertex
  std::vector<double> times_ms;              //!< time of each frame (ms)
  std::vector<std::vector<Vec3>> positions;  //!< per frame, base vertex positions (mm)
  std::vector<std::vector<Vec3>> normals;    //!< per frame, base vertex unit normals (of the fine mesh)
  int grid = 0;                              //!< lattice steps per edge
  std::vector<float> displacement;           //!< [frame][triangle][sample] (mm along the patch normal)
  std::size_t missed = 0;                    //!< samples whose normal line missed the fine surface (0 there)
  double max_abs_displacement = 0.0;         //!< largest |displacement| stored (mm)
};

//! Samples per triangle of a lattice with `grid` steps per edge.
inline std::size_t patch_samples(int grid) {
  return static_cast<std::size_t>(grid + 1) * static_cast<std::size_t>(grid + 2) / 2;
}

//! Index of lattice sample (i, j), i + j <= grid: barycentric weights (1 - i/g - j/g, i/g, j/g) of
//! the triangle's corners 0, 1, 2.
inline std::size_t patch_sample_index(int grid, int i, int j) {
  return static_cast<std::size_t>(j * (grid + 1) - j * (j - 1) / 2 + i);
}

//! Builds the base mesh and bakes the displacement maps of every frame.
//! \throw InvalidInput (BadMesh) on an empty or inconsistent sequence; (Usage) on grid outside 1..64.
PatchMesh build_patch_mesh(const MeshSequence& fine, const PatchOptions& options = {});

//! A point of base triangle `tri` in `frame` at barycentric weights (1 - b1 - b2, b1, b2): the PN
//! patch, plus the displacement map (linear on the lattice) along the patch normal when `displaced`.
Vec3 patch_point(const PatchMesh& pm, std::size_t frame, std::size_t tri, double b1, double b2, bool displaced = true);

//! The displaced patches tessellated on the lattice of `level` steps per edge (level² triangles per
//! base triangle), vertices shared along base edges: the mesh the GPU path displays, as plain
//! per-frame meshes (for the classical path at the same triangle count, and for tests).
MeshSequence tessellate_patches(const PatchMesh& pm, int level);

}  // namespace c4d
