# --- fmi: FMI 2.0 co-simulation export ------------------------------------------
# mechflow_fmi_common: the FMU's variables and packed settings, which the
# exporter and the FMU's binary both use. mechflow_fmi_export: what
# `mechflow export-fmu` writes (modelDescription.xml, the zip). mechflow_fmi:
# the FMU's binary, a shared library exporting only the fmi2 functions; the
# rest of mechflow is linked into it (PIC), the shared libraries it needs
# beyond Debian's base system are copied beside it into fmu/linux64/ of the
# build tree, where RUNPATH $ORIGIN finds them, and UDUNITS' database into
# fmu/udunits/. export-fmu packs both folders.
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)
find_path(MECHFLOW_UDUNITS_XML_DIR udunits2.xml PATHS /usr/share/xml/udunits /usr/local/share/xml/udunits)
if(NOT MECHFLOW_UDUNITS_XML_DIR)
  message(FATAL_ERROR "UDUNITS-2's database udunits2.xml not found: install libudunits2-data")
endif()

add_library(mechflow_fmi_common STATIC fmi/packed_settings.cc fmi/variables.cc)
target_link_libraries(mechflow_fmi_common PUBLIC mechflow::run)
mechflow_warnings(mechflow_fmi_common)

add_library(mechflow_fmi_export STATIC fmi/export.cc fmi/model_description.cc fmi/zip_writer.cc)
target_link_libraries(mechflow_fmi_export PUBLIC mechflow_fmi_common PRIVATE tinyxml2::tinyxml2 PkgConfig::LIBZIP)
mechflow_warnings(mechflow_fmi_export)

add_library(mechflow_fmi SHARED fmi/fmi2_functions.cc fmi/instance.cc)
target_link_libraries(mechflow_fmi PRIVATE mechflow_fmi_common)
# Every library the FMU needs is a direct dependency (DT_NEEDED) of it, found
# beside it through RUNPATH $ORIGIN: the dynamic loader searches a
# library's own RUNPATH only for that library's direct dependencies, so
# those of SUNDIALS' KLU solver, KLU and UDUNITS-2 are named here too
# (fmi/collect_runtime.cmake refuses a copied library the binary does not name).
find_library(MECHFLOW_EXPAT_LIBRARY expat REQUIRED)
foreach(lib sundials_sunmatrixsparse klu amd colamd btf suitesparseconfig)
  find_library(MECHFLOW_FMI_${lib} ${lib} REQUIRED)
  list(APPEND MECHFLOW_FMI_INDIRECT ${MECHFLOW_FMI_${lib}})
endforeach()
target_link_options(mechflow_fmi PRIVATE -Wl,--exclude-libs,ALL -Wl,--enable-new-dtags)
if(NOT (MECHFLOW_SANITIZE OR MECHFLOW_FUZZ))  # clang links the sanitizers' runtime into programs only
  target_link_options(mechflow_fmi PRIVATE -Wl,--no-undefined)
endif()
target_link_libraries(mechflow_fmi PRIVATE -Wl,--push-state,--no-as-needed ${MECHFLOW_FMI_INDIRECT}
                      ${MECHFLOW_EXPAT_LIBRARY} -Wl,--pop-state)
set_target_properties(mechflow_fmi PROPERTIES
  CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
  BUILD_RPATH "$ORIGIN" LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fmu/linux64)
mechflow_warnings(mechflow_fmi)
add_custom_command(TARGET mechflow_fmi POST_BUILD
  COMMAND ${CMAKE_COMMAND} -DLIBRARY=$<TARGET_FILE:mechflow_fmi> -DOUT=${CMAKE_BINARY_DIR}/fmu -DUNITS=${MECHFLOW_UDUNITS_XML_DIR}
          -P ${CMAKE_SOURCE_DIR}/fmi/collect_runtime.cmake
  COMMENT "Copying the FMU's shared libraries and units database into fmu/")
