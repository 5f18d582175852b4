# End-to-end cases of wave-speed (tests/e2e/wave_speed.sh). Cases that need rubber-run or dem-run are skipped
# (exit 77) when that tool is not built. The acceptance cases (lattice against Mooney-Rivlin within 2%) run a
# dozen rubber-run simulations each (minutes): label "acceptance", and they skip unless FRACTURE_ACCEPTANCE=1:
#   FRACTURE_ACCEPTANCE=1 ctest -L acceptance --output-on-failure
set(WAVE_SPEED_SCRIPT ${CMAKE_CURRENT_SOURCE_DIR}/wave_speed.sh)

foreach(case help theory pipe bad-input rubber-pipe dem-pulse)
  add_test(NAME e2e.wave-speed.${case}
           COMMAND bash ${WAVE_SPEED_SCRIPT} $<TARGET_FILE_DIR:wave-speed>
                   ${CMAKE_CURRENT_BINARY_DIR}/work/wave-speed-${case} ${case})
  set_tests_properties(e2e.wave-speed.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}"
                       SKIP_RETURN_CODE 77 TIMEOUT 600)
endforeach()

foreach(state 1.2x3 1.5x3 2x2)
  string(REPLACE "x" ";" stretch ${state})
  add_test(NAME e2e.wave-speed.acceptance-${state}
           COMMAND bash ${WAVE_SPEED_SCRIPT} $<TARGET_FILE_DIR:wave-speed>
                   ${CMAKE_CURRENT_BINARY_DIR}/work/wave-speed-acceptance-${state} acceptance ${stretch})
  set_tests_properties(e2e.wave-speed.acceptance-${state} PROPERTIES LABELS "acceptance" ENVIRONMENT
                       "${FRACTURE_TEST_ENV}" SKIP_RETURN_CODE 77 TIMEOUT 3600 RUN_SERIAL TRUE)
endforeach()
