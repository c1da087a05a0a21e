# Tests of mech/.
mechflow_test(dynamics_test unit tests/mech/dynamics_test.cc)
mechflow_test(constraints_test unit tests/mech/constraints_test.cc)
mechflow_test(quaternion_joint_test unit tests/mech/quaternion_joint_test.cc)
mechflow_test(mech_no_allocation_test unit tests/mech/no_allocation_test.cc)
mechflow_test(force_elements_test unit tests/mech/force_elements_test.cc)
