# Faults while writing (tests/e2e/faults.sh): a full disk (tmpfs in a private mount namespace, skipped
# where none can be made), a full standard output, runs killed by SIGKILL, SIGTERM and SIGINT.
foreach(case full-disk full-stdout killed terminated)
  add_test(NAME e2e.faults.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/faults.sh ${PROJECT_SOURCE_DIR} $<TARGET_FILE_DIR:dem-run>
                   ${CMAKE_CURRENT_BINARY_DIR}/work/faults-${case} ${case})
  set_tests_properties(e2e.faults.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}"
                       SKIP_REGULAR_EXPRESSION "^SKIP:")
endforeach()
