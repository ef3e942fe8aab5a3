# Tests of the phantoms stage.
c4d_add_test(phantoms_test unit/phantoms_test.cpp)
add_dependencies(phantoms_test contour4d-cli)
