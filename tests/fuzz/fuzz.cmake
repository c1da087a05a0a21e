# Fuzz targets (tests/fuzz/fuzz_target.h).
#
# Always: each target with a replay main (fuzz_replay_NAME), and a CTest
# test that runs it on the target's regression inputs and seed corpus -- every
# input that once crashed stays fixed.
# With -DMECHFLOW_FUZZ=ON and clang (scripts/fuzz.sh): each target as a
# libFuzzer binary (fuzz_NAME); the whole project is then built with
# -fsanitize=fuzzer-no-link,address,undefined (see the top CMakeLists.txt).
set(MECHFLOW_FUZZ_TARGETS diagram_loader time_function lua table results_table set_file scene)
# seed corpora: the example diagrams for the loader and the shapes, small files for the others
set(seeds_diagram_loader diagrams/examples)
set(seeds_time_function tests/fuzz/seeds/time_function)
set(seeds_lua tests/fuzz/seeds/lua)
set(seeds_table tests/fuzz/seeds/table)
set(seeds_results_table tests/fuzz/seeds/results_table)
set(seeds_set_file tests/fuzz/seeds/set_file)
set(seeds_scene diagrams/examples)
foreach(name ${MECHFLOW_FUZZ_TARGETS})
  set(source ${CMAKE_CURRENT_SOURCE_DIR}/tests/fuzz/fuzz_${name}.cc)
  add_executable(fuzz_replay_${name} ${source} tests/fuzz/replay_main.cc)
  target_link_libraries(fuzz_replay_${name} PRIVATE mechflow_cli)
  target_include_directories(fuzz_replay_${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  mechflow_warnings(fuzz_replay_${name})
  add_test(NAME fuzz_regressions_${name}
           COMMAND fuzz_replay_${name} ${CMAKE_CURRENT_SOURCE_DIR}/tests/fuzz/regressions/${name}
                   ${CMAKE_CURRENT_SOURCE_DIR}/${seeds_${name}}
           WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/diagrams/examples)
  set_tests_properties(fuzz_regressions_${name} PROPERTIES LABELS unit TIMEOUT 300)
  if(MECHFLOW_FUZZ)
    add_executable(fuzz_${name} ${source})
    target_link_libraries(fuzz_${name} PRIVATE mechflow_cli)
    target_include_directories(fuzz_${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
    target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  endif()
endforeach()
