# Tests of the io stage: stack validation, contour readers (JSON, GPFile), input dispatch, `extract`.
c4d_add_test(stack_test unit/stack_test.cpp unit/contour_repair_test.cpp)
c4d_add_test(contours_json_test unit/contours_json_test.cpp)
c4d_add_test(gpfile_test unit/gpfile_test.cpp)
c4d_add_test(input_test unit/input_test.cpp)
# input_test runs the CLI.
add_dependencies(input_test contour4d-cli)
c4d_add_test(repair_cli_test unit/repair_cli_test.cpp)
add_dependencies(repair_cli_test contour4d-cli)
