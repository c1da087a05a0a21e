# Tests of diagrams/.
