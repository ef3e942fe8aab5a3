# Sources of the connect stage (paths relative to src/).
