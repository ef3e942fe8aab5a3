# Sources of the connect stage (paths relative to src/).
target_sources(contour4d PRIVATE
  connect/similarity.cpp
  connect/connectivity.cpp)
