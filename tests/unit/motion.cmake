c4d_add_test(motion_test unit/motion_test.cpp)
c4d_add_test(reconstruct4d_test unit/reconstruct4d_test.cpp)
add_dependencies(reconstruct4d_test contour4d-cli)
c4d_add_test(contour_fit_test unit/contour_fit_test.cpp)
