# glTF export of a 4D mesh (paths relative to src/).
target_sources(contour4d PRIVATE
  io/gltf.cpp)
