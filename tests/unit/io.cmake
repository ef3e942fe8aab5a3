# Tests of the io stage: stack validation, contour readers (JSON, GPFile), input dispatch, `extract`.
c4d_add_test(stack_test unit/stack_test.cpp)
c4d_add_test(contours_json_test unit/contours_json_test.cpp)
c4d_add_test(gpfile_test unit/gpfile_test.cpp)
c4d_add_test(input_test unit/input_test.cpp)
# input_test runs the CLI.
add_dependencies(input_test contour4d-cli)
