# Tests of the temporal stage (compact model, interpolation, glTF) and of the renderer.
c4d_add_test(compact_test unit/compact_test.cpp)
target_link_libraries(compact_test PRIVATE zstd::libzstd_shared)  # hand-made zstd frames for the model.c4d tests
c4d_add_test(interpolate_test unit/interpolate_test.cpp)
c4d_add_test(gltf_test unit/gltf_test.cpp)
target_link_libraries(gltf_test PRIVATE TinyGLTF::TinyGLTF)
if(OpenGL_EGL_FOUND)  # contour4d_render is defined by src/render/CMakeLists.txt (added later; linking by name is fine)
  c4d_add_test(render_test unit/render_test.cpp)
  target_link_libraries(render_test PRIVATE contour4d_render)
endif()
