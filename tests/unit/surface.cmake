# Tests of the surface stage (connectivity, tiling, caps, one-frame reconstruction).
c4d_add_test(similarity_test unit/similarity_test.cpp)
c4d_add_test(connectivity_test unit/connectivity_test.cpp)
c4d_add_test(tiling_test unit/tiling_test.cpp)
c4d_add_test(reconstruct_test unit/reconstruct_test.cpp)
c4d_add_test(delaunay_tiling_test unit/delaunay_tiling_test.cpp)
c4d_add_test(angle_repair_test unit/angle_repair_test.cpp)
c4d_add_test(isotropic_remesh_test unit/isotropic_remesh_test.cpp)
c4d_add_test(surface_walk_test unit/surface_walk_test.cpp)
