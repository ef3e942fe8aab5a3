# find_package only; every dependency comes from a Debian 12 package (scripts/setup.sh installs them).
# A missing one stops configuration with the apt package to install.
macro(c4d_require name package)
  find_package(${name} ${ARGN} QUIET)
  if(NOT ${name}_FOUND)
    message(FATAL_ERROR "contour4d needs ${name}: run scripts/setup.sh or `apt-get install ${package}`")
  endif()
endmacro()

c4d_require(Eigen3 libeigen3-dev NO_MODULE)
c4d_require(CGAL libcgal-dev)
c4d_require(nlohmann_json nlohmann-json3-dev)
c4d_require(fmt libfmt-dev)
c4d_require(TBB libtbb-dev)
c4d_require(CLI11 libcli11-dev)
if(C4D_BUILD_TESTS)
  c4d_require(GTest libgtest-dev)
endif()
if(C4D_BUILD_BENCH)
  c4d_require(benchmark libbenchmark-dev)
endif()

# ITK: medical image I/O (NIfTI, NRRD, MetaImage, DICOM via GDCM) for label masks and DICOM geometry.
c4d_require(ITK libinsighttoolkit5-dev COMPONENTS ITKCommon ITKIOImageBase ITKIONIFTI ITKIONRRD ITKIOMeta ITKIOGDCM ITKGDCM)

# DICOM RT structure sets: DCMTK's dcmrt (and dcmdata, which parses the file).
c4d_require(DCMTK libdcmtk-dev CONFIG)

# glTF export: tinygltf and meshoptimizer.
c4d_require(TinyGLTF libtinygltf-dev)
c4d_require(meshoptimizer libmeshoptimizer-dev)

# model.c4d: the payload is one zstd frame (docs/compact.md).
c4d_require(zstd libzstd-dev)

# TetGen 1.5 (the cavity's volume mesh for `contour4d export`, src/solver/cavity_mesh.cpp). Debian's libtet1.5-dev
# ships a header and a library but no CMake package file, so it is found by path and wrapped in an imported target.
find_path(TETGEN_INCLUDE_DIR tetgen.h)
find_library(TETGEN_LIBRARY NAMES tet)
if(NOT TETGEN_INCLUDE_DIR OR NOT TETGEN_LIBRARY)
  message(FATAL_ERROR "contour4d needs TetGen: run scripts/setup.sh or `apt-get install libtet1.5-dev`")
endif()
add_library(TetGen::TetGen UNKNOWN IMPORTED)
set_target_properties(TetGen::TetGen PROPERTIES IMPORTED_LOCATION "${TETGEN_LIBRARY}"
                                                INTERFACE_INCLUDE_DIRECTORIES "${TETGEN_INCLUDE_DIR}")

# Headless rendering (EGL + OpenGL, Mesa's llvmpipe where there is no GPU); the viewer's window (GLFW) is
# optional and looked for in src/render/CMakeLists.txt.
find_package(OpenGL COMPONENTS OpenGL EGL)
