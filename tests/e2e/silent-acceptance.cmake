# Input once accepted silently, now refused naming the fault (tests/e2e/silent_acceptance.sh).
foreach(case run-frames nan-frame overlap repeated-key nested-config config-file ignored-option scene-values same-input)
  add_test(NAME e2e.fault.silent-${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/silent_acceptance.sh ${PROJECT_SOURCE_DIR} $<TARGET_FILE_DIR:dem-run>
                   ${CMAKE_CURRENT_BINARY_DIR}/work/silent-${case} ${case})
  set_tests_properties(e2e.fault.silent-${case} PROPERTIES LABELS "e2e;fault" ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()
