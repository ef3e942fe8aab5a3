# Sources of the phantoms stage (paths relative to src/).
target_sources(contour4d PRIVATE phantoms/phantom.cpp phantoms/rasterize.cpp)
