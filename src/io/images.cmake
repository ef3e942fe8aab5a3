# Label images and DICOM-referenced contours (ITK), paths relative to src/.
target_sources(contour4d PRIVATE
  io/images.cpp
  io/sunnybrook.cpp)
