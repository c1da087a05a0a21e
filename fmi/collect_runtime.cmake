# Copies the shared libraries LIBRARY needs, except the base system's (the C
# and C++ runtimes, which every Linux importer has), beside it into
# OUT/linux64, and UDUNITS-2's database (the XML files of folder UNITS) into OUT/udunits. Run after LIBRARY
# is linked (fmi/fmi.cmake).
# the copies of an earlier build go first: RUNPATH $ORIGIN would find them
file(GLOB old ${OUT}/linux64/*.so.*)
if(old)
  file(REMOVE ${old})
endif()
file(GET_RUNTIME_DEPENDENCIES
  LIBRARIES ${LIBRARY}
  RESOLVED_DEPENDENCIES_VAR resolved
  UNRESOLVED_DEPENDENCIES_VAR unresolved
  PRE_EXCLUDE_REGEXES "^(ld-linux|libc|libm|libstdc\\+\\+|libgcc_s|libpthread|libdl|librt)\\.so")
if(unresolved)
  message(FATAL_ERROR "the FMU's binary needs libraries that were not found: ${unresolved}")
endif()
# the libraries the binary names itself (DT_NEEDED): only these are found through its RUNPATH
execute_process(COMMAND readelf -d ${LIBRARY} OUTPUT_VARIABLE dynamic RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "readelf -d ${LIBRARY} failed")
endif()
foreach(lib ${resolved})
  get_filename_component(name ${lib} NAME)
  if(name MATCHES "^(ld-linux|libc|libm|libstdc\\+\\+|libgcc_s|libpthread|libdl|librt)[.-]")
    continue()
  endif()
  string(FIND "${dynamic}" "[${name}]" named)
  if(named EQUAL -1)
    message(FATAL_ERROR "${name}, which the FMU's binary needs through another library, is not named by the "
                        "binary itself, so its RUNPATH would not find it: add it to MECHFLOW_FMI_INDIRECT (fmi/fmi.cmake)")
  endif()
  # by the name the loader asks for (the soname the link recorded), the file's content
  file(REAL_PATH ${lib} real)
  configure_file(${real} ${OUT}/linux64/${name} COPYONLY)
endforeach()
file(GLOB units ${UNITS}/*.xml)
file(MAKE_DIRECTORY ${OUT}/udunits)
file(COPY ${units} DESTINATION ${OUT}/udunits)
