c4d_add_test(motion_test unit/motion_test.cpp)
