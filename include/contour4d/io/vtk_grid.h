#pragma once
//! \file vtk_grid.h
//! \brief VTK XML files with data arrays: a tetrahedral UnstructuredGrid (.vtu) and PolyData with point and
//! cell arrays (.vtp), written without VTK (raw appended binary, UInt64 headers, little endian), read by VTK's
//! own readers, meshio and the flow solvers that load SimVascular's mesh-complete folders.

#include <cstdint>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/tet_mesh.h"

namespace c4d {

//! One named data array: Int32 values, or Float64 tuples of `components` values.
struct VtkArray {
  std::string name;
  int components = 1;              //!< values per tuple (Float64 arrays)
  std::vector<std::int32_t> ints;  //!< an Int32 array when not empty
  std::vector<double> doubles;     //!< else a Float64 array, tuple after tuple
};

//! The point and cell arrays of a dataset.
struct VtkData {
  std::vector<VtkArray> points;
  std::vector<VtkArray> cells;
};

//! A .vtp of triangles with data arrays (Float64 points, Int64 connectivity). `comment` goes in an XML comment.
std::string format_vtp_data(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                            const VtkData& data, const std::string& comment = {});

//! A .vtu of tetrahedra (VTK cell type 10) with data arrays. `comment` goes in an XML comment.
std::string format_vtu_tets(const std::vector<Vec3>& points, const std::vector<Tet>& tets, const VtkData& data,
                            const std::string& comment = {});

}  // namespace c4d
