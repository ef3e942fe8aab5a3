# Tests of the phantoms stage.
