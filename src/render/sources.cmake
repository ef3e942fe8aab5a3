# Sources of the render stage (paths relative to src/).
