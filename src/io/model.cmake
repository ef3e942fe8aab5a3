# Compact 4D model file and glTF export (paths relative to src/).
target_sources(contour4d PRIVATE
  io/model_c4d.cpp
  io/gltf.cpp)
