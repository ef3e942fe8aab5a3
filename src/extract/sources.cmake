# Sources of the extract stage (paths relative to src/).
target_sources(contour4d PRIVATE
  extract/marching_squares.cpp
  extract/mask_contours.cpp)
