# Tests of cli/.
mechflow_test(cli_test unit tests/cli/cli_test.cc)
mechflow_test(modes_test unit tests/cli/modes_test.cc)
mechflow_test(modes_command_test unit tests/cli/modes_command_test.cc)
mechflow_test(figures_test unit tests/cli/figures_test.cc)
mechflow_test(sweep_test unit tests/cli/sweep_test.cc)
if(MECHFLOW_MPI)
  target_compile_definitions(sweep_test PRIVATE MECHFLOW_MPIEXEC="${MPIEXEC_EXECUTABLE}")
endif()
