# Every test executable, one line each: mechflow_test(name label sources...).
include(tests/mech/tests.cmake)
include(tests/blocks/tests.cmake)
include(tests/scripting/tests.cmake)
include(tests/diagrams/tests.cmake)
include(tests/analysis/tests.cmake)
include(tests/regression/tests.cmake)
include(tests/cli/tests.cmake)
include(tests/fuzz/fuzz.cmake)
