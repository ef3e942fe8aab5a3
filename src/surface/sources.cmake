# Sources of the surface stage (paths relative to src/).
target_sources(contour4d PRIVATE
  surface/resample.cpp
  surface/tiling.cpp
  surface/delaunay_tiling.cpp
  surface/capping.cpp
  surface/smoothing.cpp
  surface/fairing.cpp
  surface/refine.cpp
  surface/isotropic_remesh.cpp
  surface/angle_repair.cpp
  surface/mesh_check.cpp
  surface/reconstruct.cpp)
