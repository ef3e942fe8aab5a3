# Tests of the io stage.
