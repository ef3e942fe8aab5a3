#pragma once
//! \file tet_untangle.h
//! \brief Untangling a moved tetrahedral mesh: its free nodes moved so that no tet is inverted and each stays
//! close to its shape in a reference mesh.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "contour4d/core/tet_mesh.h"
#include "contour4d/core/vec.h"

namespace c4d {

//! Each node's tets, in compressed rows: the tets of node v are stars[offsets[v] .. offsets[v + 1]).
struct NodeStars {
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> stars;
};

//! The stars of every node of `tets` (`node_count` nodes), each star's tets ascending.
NodeStars node_stars(std::size_t node_count, const std::vector<Tet>& tets);

//! What untangle_tets does.
struct UntangleOptions {
  int sweeps = 20;           //!< at most this many Gauss-Seidel sweeps over the free region
  int quality_sweeps = 4;    //!< sweeps go on (up to this many) while a tet is flatter than max_aspect
  int node_steps = 30;       //!< descent steps per node and sweep
  double max_aspect = 20.0;  //!< a tet flatter than this aspect ratio (about 3° dihedral) joins the free region
  double epsilon = 1e-3;     //!< Escobar's ε: below this relative volume a tet's volume is regularised
};

//! Moves the free nodes (index >= `fixed_nodes`) of the tets at `x` until no tet is inverted, by minimising each
//! node's sum of Escobar et al.'s regularised shape distortion (CMAME 192, 2003, "Simultaneous untangling and
//! smoothing of tetrahedral meshes") over its star, measured against the tet's shape at `reference`. The free
//! region starts with the free nodes of the inverted and flat tets (aspect ratio above options.max_aspect) and
//! their neighbours, and grows by one ring of tets per sweep while a tet stays inverted. Nodes are visited in
//! ascending order, so the result depends on nothing but the input. Returns the number of nodes moved; `x` is
//! left with the tets inverted that the sweeps could not undo (the caller checks).
std::size_t untangle_tets(std::vector<Vec3>& x, const std::vector<Vec3>& reference, const std::vector<Tet>& tets,
                          std::size_t fixed_nodes, const NodeStars& stars, const UntangleOptions& options = {});

}  // namespace c4d
