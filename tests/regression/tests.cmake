# Tests of regression/.
