#pragma once
//! \file obj.h
//! \brief Wavefront OBJ (positions and triangles; mm) for tools without VTK support.

#include <string>

#include "contour4d/core/mesh.h"

namespace c4d {

//! OBJ text: a comment header (units, space), `v x y z` with 9 decimals, `f a b c` 1-based.
std::string format_obj(const TriangleMesh& mesh, const std::string& comment = {});

//! Parses `v` and `f` records (polygons fanned to triangles; `f a/b/c` forms accepted).
//! \throw IoError (BadMesh) naming `source` and the line.
TriangleMesh parse_obj(const std::string& content, const std::string& source);

}  // namespace c4d
