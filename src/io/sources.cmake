# Sources of the io stage (paths relative to src/).
target_sources(contour4d PRIVATE
  io/output_dir.cpp
  io/vtk_xml.cpp
  io/obj.cpp
  io/mesh_output.cpp)
include(io/readers.cmake)
include(io/model.cmake)
include(io/images.cmake)
