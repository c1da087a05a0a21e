# Checks of the project's text: nothing points outside the clone.
add_test(NAME no_outside_references COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tests/docs/no_outside_references.sh)
set_tests_properties(no_outside_references PROPERTIES LABELS docs SKIP_RETURN_CODE 77 TIMEOUT 60)
