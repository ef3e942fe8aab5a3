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

# Headless rendering (EGL + OpenGL, Mesa's llvmpipe where there is no GPU); the viewer's window (GLFW) is
# optional and looked for in src/render/CMakeLists.txt.
find_package(OpenGL COMPONENTS OpenGL EGL)
