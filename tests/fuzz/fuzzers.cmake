# Fuzz targets of the contour readers; seed corpora: tests/corpus/contours_json, tests/corpus/gpfile/*.
c4d_add_fuzzer(fuzz_contours_json fuzz_contours_json.cpp)
c4d_add_fuzzer(fuzz_gpfile fuzz_gpfile.cpp)
