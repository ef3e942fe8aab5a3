# Sources of the motion stage (paths relative to src/).
target_sources(contour4d PRIVATE
  motion/rbf.cpp
  motion/contour_fit.cpp
  motion/contour_matching.cpp
  motion/corner_snap.cpp
  motion/section.cpp
  motion/chains.cpp
  motion/carry.cpp
  motion/morph.cpp
  motion/morph_match.cpp
  motion/morph_relax.cpp
  motion/morph_snap.cpp
  motion/morph_fit.cpp
  motion/simd_avx.cpp
  motion/reconstruct4d.cpp)
# The morph's four-lane steps (relaxation sweeps, RBF sums) are compiled for AVX; morph_relax.cpp and rbf.cpp
# call them only where the CPU has AVX (the result is the same bit for bit either way).
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$" AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  set_source_files_properties(motion/simd_avx.cpp TARGET_DIRECTORY contour4d PROPERTIES COMPILE_OPTIONS "-mavx")
endif()
