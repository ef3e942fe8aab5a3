# The pipeline layer (paths relative to src/): the end-to-end runs shared by the CLI and the Python module.
target_sources(contour4d PRIVATE
  pipeline/input.cpp
  pipeline/reconstruct_run.cpp
  pipeline/pack_run.cpp
  pipeline/structures.cpp
  pipeline/structures_run.cpp)
