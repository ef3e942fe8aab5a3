#pragma once
// Raw little-endian bytes for the VTK XML writers' appended data (vtk_xml.cpp, vtk_grid.cpp).

#include <cstring>
#include <string>

namespace c4d {

//! Appends the bytes of `v` to `out` as they lie in memory.
template <class T>
void append_raw(std::string& out, const T& v) {
  char buf[sizeof(T)];
  std::memcpy(buf, &v, sizeof(T));  // the library targets little-endian hosts (x86-64, arm64)
  out.append(buf, sizeof(T));
}

}  // namespace c4d
