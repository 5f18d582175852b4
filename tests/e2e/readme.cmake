# Every command of README.md, run as documented (included by tests/e2e/CMakeLists.txt).
add_test(NAME e2e.readme.commands
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/readme_commands.sh ${PROJECT_SOURCE_DIR} ${CMAKE_BINARY_DIR}
                 ${CMAKE_CURRENT_BINARY_DIR}/work/readme)
set_tests_properties(e2e.readme.commands PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}" TIMEOUT 600)
