# End-to-end cases of rubber-run (included by tests/e2e/CMakeLists.txt): help and version, mesh-gen | rubber-run
# to a file and to standard output, reproducibility (a second run, 1 and 2 threads, another seed), refusals of
# bad input (exit 2, the fault named, no output left), the far-field and short-bond warnings, a wave run, and
# energy-neutral failure with a crack path (frozen energy observed, energy conserved, 1 and 2 threads alike).
foreach(case help pipe reproducible bad-input far-field wave freeze)
  add_test(NAME e2e.rubber-run.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/rubber_run.sh $<TARGET_FILE_DIR:rubber-run> ${PROJECT_SOURCE_DIR}/data/scenes
                   ${CMAKE_CURRENT_BINARY_DIR}/work/rubber-run-${case} ${case})
  set_tests_properties(e2e.rubber-run.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()
