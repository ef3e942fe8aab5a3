# Sources of the topology-change step of the motion stage (paths relative to src/).
target_sources(contour4d PRIVATE
  motion/vertical_deformation.cpp)
