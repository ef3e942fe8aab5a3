# Sources of the surface stage (paths relative to src/).
