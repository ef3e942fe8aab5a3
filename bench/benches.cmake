# Benchmarks of the extract stage (bench/CMakeLists.txt includes this file).
add_executable(extract_bench ${CMAKE_CURRENT_LIST_DIR}/extract_bench.cpp)
target_link_libraries(extract_bench PRIVATE benchmark::benchmark contour4d TBB::tbb)
c4d_set_warnings(extract_bench)
# Tables I and II of Miara et al.: compact model size and classical-vs-compact playback (issue 6).
# Table I against per-frame marching cubes meshes: bench/storage_table.sh (a script, not a target).
if(TARGET contour4d_render OR OpenGL_EGL_FOUND)
  add_executable(playback_bench playback_bench.cpp)
  target_link_libraries(playback_bench PRIVATE contour4d contour4d_render)
  c4d_set_warnings(playback_bench)
endif()
# Issue 4: the whole 4D run of the 20-frame left-heart cycle, against the paper's figure and method.
add_executable(morph_bench ${CMAKE_CURRENT_LIST_DIR}/morph_bench.cpp)
target_link_libraries(morph_bench PRIVATE benchmark::benchmark contour4d TBB::tbb)
c4d_set_warnings(morph_bench)
# One-frame surface speed (issue 3): output vertices per second for phantoms and bivme frame 0.
add_executable(surface_bench ${CMAKE_CURRENT_LIST_DIR}/surface_bench.cpp)
target_link_libraries(surface_bench PRIVATE benchmark::benchmark contour4d)
target_compile_definitions(surface_bench PRIVATE C4D_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data")
c4d_set_warnings(surface_bench)
