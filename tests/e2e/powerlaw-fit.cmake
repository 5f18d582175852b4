# End-to-end cases of powerlaw-fit (included by tests/e2e/CMakeLists.txt). The helper writes seeded inputs:
# a column of power-law numbers, a fragments file as fragment-count writes it, and a fragments file with bad masses.
add_executable(powerlaw_fit_make_input ${CMAKE_CURRENT_SOURCE_DIR}/powerlaw_fit_make_input.cpp)
target_link_libraries(powerlaw_fit_make_input PRIVATE fracture fracture_warnings)
set_target_properties(powerlaw_fit_make_input PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests/e2e)

foreach(case help text pipe reproducible cell-count pooled xmax bad-input chain reference)
  add_test(NAME e2e.powerlaw-fit.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/powerlaw_fit.sh $<TARGET_FILE_DIR:powerlaw-fit>
                   $<TARGET_FILE:powerlaw_fit_make_input> ${CMAKE_CURRENT_BINARY_DIR}/work/powerlaw-fit-${case} ${case}
                   ${CMAKE_SOURCE_DIR}/docs/powerlaw-fit.md)
  set_tests_properties(e2e.powerlaw-fit.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()
# Agreement with R poweRlaw (Debian r-cran-powerlaw): skipped (exit 77) when R or the package is missing.
set_tests_properties(e2e.powerlaw-fit.reference PROPERTIES LABELS "e2e;reference" SKIP_RETURN_CODE 77)
# The DESIGN chain mesh-gen -> run -> fragment-count -> powerlaw-fit (skipped when fragment-count's helper is absent).
set_tests_properties(e2e.powerlaw-fit.chain PROPERTIES SKIP_RETURN_CODE 77)
