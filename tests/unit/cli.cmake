# Tests of the cli stage.
c4d_add_test(cli_test unit/cli_test.cpp)
c4d_add_test(myocardium_test unit/myocardium_test.cpp)
