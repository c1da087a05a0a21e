# Tests of mech/.
mechflow_test(dynamics_test unit tests/mech/dynamics_test.cc)
