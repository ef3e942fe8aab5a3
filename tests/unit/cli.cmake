# Tests of the cli stage.
c4d_add_test(cli_test unit/cli_test.cpp)
