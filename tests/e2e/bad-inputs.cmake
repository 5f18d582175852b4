# Bad input refused by every tool that reads it, and runaway runs stopped (tests/e2e/bad_inputs.sh).
foreach(case meshes options runaway)
  add_test(NAME e2e.bad-inputs.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bad_inputs.sh ${PROJECT_SOURCE_DIR} $<TARGET_FILE_DIR:dem-run>
                   ${CMAKE_CURRENT_BINARY_DIR}/work/bad-inputs-${case} ${case})
  set_tests_properties(e2e.bad-inputs.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()
