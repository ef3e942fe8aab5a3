# Sources of the phantoms stage (paths relative to src/).
