# Sources of the temporal stage (paths relative to src/).
target_sources(contour4d PRIVATE
  temporal/compact.cpp
  temporal/displacement_map.cpp
  temporal/interpolate.cpp
  temporal/sequence.cpp
  temporal/model_c4d.cpp)
