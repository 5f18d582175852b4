# End-to-end cases of dem-run (included by tests/e2e/CMakeLists.txt): help and version, refusals of bad
# input (exit 2, the fault named, no output left), mesh-gen | dem-run, reproducibility (a second run,
# 1 and 2 threads), short explosion and impact runs to their stop rule, and integrator.start.
foreach(case help bad-input pipe reproducible explosion impact start beams-off)
  add_test(NAME e2e.dem-run.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/dem_run.sh $<TARGET_FILE_DIR:dem-run> ${PROJECT_SOURCE_DIR}/data/scenes
                   ${CMAKE_CURRENT_BINARY_DIR}/work/dem-run-${case} ${case})
  set_tests_properties(e2e.dem-run.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()
