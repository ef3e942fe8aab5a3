# Sources of the metrics stage (paths relative to src/). CGAL is included only by
# triangle_distance.cpp (AABB tree) and topology.cpp (box intersection, exact predicates).
target_sources(contour4d PRIVATE
  metrics/surface_projector.cpp
  metrics/surface_walk.cpp
  metrics/triangle_distance.cpp
  metrics/distance.cpp
  metrics/conformity.cpp
  metrics/quality.cpp
  metrics/topology.cpp
  metrics/result_check.cpp
  metrics/correspondence.cpp
  metrics/volume.cpp
  metrics/evaluation.cpp)
