# Sources of the motion stage (paths relative to src/).
target_sources(contour4d PRIVATE
  motion/rbf.cpp
  motion/contour_fit.cpp
  motion/contour_matching.cpp
  motion/section.cpp
  motion/morph.cpp
  motion/reconstruct4d.cpp)
