# Sources of the readers (contour JSON, GPFile), paths relative to src/.
target_sources(contour4d PRIVATE
  io/contours_json.cpp
  io/gpfile.cpp)
