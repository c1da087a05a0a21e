# Tests of mech/.
mechflow_test(dynamics_test unit tests/mech/dynamics_test.cc)
mechflow_test(sliding_dynamics_test unit tests/mech/sliding_dynamics_test.cc)
mechflow_test(constraints_test unit tests/mech/constraints_test.cc)
mechflow_test(quaternion_joint_test unit tests/mech/quaternion_joint_test.cc)
# Counting allocations replaces malloc, which AddressSanitizer owns: these
# run in the Release suite only.
if(NOT MECHFLOW_SANITIZE AND NOT MECHFLOW_FUZZ)
  mechflow_test(mech_no_allocation_test unit tests/mech/no_allocation_test.cc OWN_EXECUTABLE)
endif()
mechflow_test(force_elements_test unit tests/mech/force_elements_test.cc)
mechflow_test(friction_hysteresis_test unit tests/mech/friction_hysteresis_test.cc)
mechflow_test(stick_slip_test unit tests/mech/stick_slip_test.cc)
mechflow_test(gear_pitch_test unit tests/mech/gear_pitch_test.cc)
mechflow_test(energy_sensor_test unit tests/mech/energy_sensor_test.cc)

# the P4 reference (bench/pendulum_chain_direct.*) checked against closed forms; its library is
# defined in bench/, which is added here, excluded from all, when the benchmarks are off
if(NOT MECHFLOW_BUILD_BENCH)
  add_subdirectory(${PROJECT_SOURCE_DIR}/bench ${PROJECT_BINARY_DIR}/bench EXCLUDE_FROM_ALL)
endif()
# (its own executable: it counts malloc calls)
mechflow_test(pendulum_chain_reference_test unit tests/mech/pendulum_chain_reference_test.cc OWN_EXECUTABLE
              LINK mechflow_bench_reference)

# the P1-P3 reference (bench/friction_direct.*) against closed forms, and the generated diagrams
# (bench/friction_diagram.*) run by mechflow against it
mechflow_test(friction_reference_test unit tests/mech/friction_reference_test.cc LINK mechflow_bench_friction)
mechflow_test(contact_stick_test unit tests/mech/contact_stick_test.cc)
