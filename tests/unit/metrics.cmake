# Tests of the metrics stage.
c4d_add_test(metrics_measures_test unit/metrics_measures_test.cpp)
c4d_add_test(result_check_test unit/result_check_test.cpp)
c4d_add_test(evaluate_cli_test unit/evaluate_cli_test.cpp)
