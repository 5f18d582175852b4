# Nothing lost, whatever the user types or the machine does (tests/e2e/nothing_lost.sh): outputs that would
# replace an input, devices and FIFOs as outputs, checkpoints on a full disk and past a file size limit, every
# writer past a file size limit, every reader short of memory, endless and binary streams as inputs.
if(FRACTURE_SANITIZE)
  set(NOTHING_LOST_SANITIZED 1)
else()
  set(NOTHING_LOST_SANITIZED 0)
endif()
foreach(case clobber devices checkpoints file-size memory endless)
  add_test(NAME e2e.fault.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/nothing_lost.sh ${PROJECT_SOURCE_DIR} $<TARGET_FILE_DIR:dem-run>
                   ${CMAKE_CURRENT_BINARY_DIR}/work/fault-${case} ${case} ${NOTHING_LOST_SANITIZED})
  set_tests_properties(e2e.fault.${case} PROPERTIES LABELS "e2e;fault" ENVIRONMENT "${FRACTURE_TEST_ENV}"
                       SKIP_REGULAR_EXPRESSION "^SKIP:" TIMEOUT 600)
endforeach()
