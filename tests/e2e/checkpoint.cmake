# End-to-end cases of checkpoints and resume (included by tests/e2e/CMakeLists.txt): runs killed at random
# steps and continued on other thread counts (explosion, impact, a uniaxial test with moving boundaries, a
# rubber crack with toughening), stop signals, and checkpoints of another run.
foreach(case explosion impact uniaxial rubber-toughening signals other-run)
  add_test(NAME e2e.checkpoint.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint.sh $<TARGET_FILE_DIR:dem-run> ${PROJECT_SOURCE_DIR}/data/scenes
                   ${CMAKE_CURRENT_BINARY_DIR}/work/checkpoint-${case} ${case})
  set_tests_properties(e2e.checkpoint.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}" TIMEOUT 300)
endforeach()
