# Sources of the readers (contour JSON, GPFile, input dispatch), paths relative to src/.
