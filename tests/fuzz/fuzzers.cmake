# Fuzz targets of the readers; seed corpora: tests/corpus/contours_json, tests/corpus/gpfile/*,
# tests/corpus/model_c4d.
c4d_add_fuzzer(fuzz_contours_json fuzz_contours_json.cpp)
c4d_add_fuzzer(fuzz_gpfile fuzz_gpfile.cpp)
c4d_add_fuzzer(fuzz_model_c4d fuzz_model_c4d.cpp)
target_link_libraries(fuzz_model_c4d PRIVATE zstd::libzstd_shared)  # wraps inputs in zstd frames
