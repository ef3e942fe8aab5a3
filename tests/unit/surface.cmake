# Tests of the surface stage.
