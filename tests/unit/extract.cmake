# Tests of the extract stage: marching squares, label images (ITK), Sunnybrook DICOM contours.
c4d_add_test(marching_squares_test unit/marching_squares_test.cpp)
c4d_add_test(images_test unit/images_test.cpp)
target_link_libraries(images_test PRIVATE TBB::tbb)
c4d_add_test(sunnybrook_test unit/sunnybrook_test.cpp)
