# The Python module's tests (unittest), labelled python: each file a CTest
# test, run by the interpreter the module is built for, importing it from the
# build tree; the mechflow command gives the reference numbers.
if(MECHFLOW_WITH_PYTHON)
  foreach(name run run_many errors analysis interrupt pip pandas_plot fit_friction)
    add_test(NAME python.${name} COMMAND ${Python_EXECUTABLE} -m unittest -v test_${name}
             WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}/tests/python)
    set_tests_properties(python.${name} PROPERTIES LABELS python ENVIRONMENT
      "PYTHONPATH=${CMAKE_BINARY_DIR}/python;PYTHONDONTWRITEBYTECODE=1;MECHFLOW_BINARY=$<TARGET_FILE:mechflow>;MECHFLOW_SOURCE_DIR=${CMAKE_SOURCE_DIR};MECHFLOW_BUILD_DIR=${CMAKE_BINARY_DIR};TEST_TMPDIR=${MECHFLOW_TEST_TMPDIR}")
  endforeach()
  set_tests_properties(python.pip PROPERTIES TIMEOUT 600)
endif()
