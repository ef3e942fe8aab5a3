# Warning flags for our own targets; C4D_STRICT makes them errors (on in CI).
function(c4d_set_warnings target)
  # GCC 12 at -O3 reports -Wrestrict inside libstdc++'s std::string operator+ (GCC bug 105329):
  # a false positive, so that one warning is off for GCC.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wno-unused-parameter
    $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>
    $<$<BOOL:${C4D_STRICT}>:-Werror>)
endfunction()

# The AVX kernels are compiled where the build can enable AVX for one file (x86-64, GCC or clang); core/cpu.cpp
# is told so (C4D_AVX_KERNELS), and its avx_available() then asks the CPU.
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$" AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  set(C4D_AVX_KERNELS ON)
else()
  set(C4D_AVX_KERNELS OFF)
endif()

# c4d_avx_source(file): a source of the library compiled with AVX enabled (where C4D_AVX_KERNELS). Its kernels
# are called only where the CPU runs AVX (core/cpu.h) and give the same bits as their SSE2 forms.
function(c4d_avx_source source)
  if(C4D_AVX_KERNELS)
    set_source_files_properties(${source} TARGET_DIRECTORY contour4d PROPERTIES COMPILE_OPTIONS "-mavx")
  endif()
endfunction()

if(C4D_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

if(C4D_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "C4D_BUILD_FUZZ needs clang: configure with CC=clang CXX=clang++")
  endif()
  # Coverage instrumentation for the whole library; the fuzz targets add the libFuzzer main.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
