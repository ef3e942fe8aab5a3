# Sources of the metrics stage (paths relative to src/).
