# Tests of fmi/: the exported FMU driven through its C interface (label fmi;
# the sanitizer suite leaves out the one that loads the FMU alone, see
# scripts/test-sanitizers.sh).
find_package(PkgConfig REQUIRED)
mechflow_test(fmi_export_test fmi tests/fmi/export_test.cc LINK PkgConfig::LIBZIP tinyxml2::tinyxml2 ${CMAKE_DL_LIBS})
