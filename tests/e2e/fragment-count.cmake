# End-to-end cases of fragment-count (included by tests/e2e/CMakeLists.txt). The helper builds run
# files from meshes with beams broken by rule, standing in for dem-run; bench/fragment_count.sh uses it too.
add_executable(fragment_count_make_run ${CMAKE_CURRENT_SOURCE_DIR}/fragment_count_make_run.cpp)
target_link_libraries(fragment_count_make_run PRIVATE fracture fracture_warnings)
set_target_properties(fragment_count_make_run PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests/e2e)

foreach(case help pipe known-clusters frames bad-input)
  add_test(NAME e2e.fragment-count.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fragment_count.sh $<TARGET_FILE_DIR:fragment-count>
                   $<TARGET_FILE:fragment_count_make_run> ${CMAKE_CURRENT_BINARY_DIR}/work/fragment-count-${case} ${case})
  set_tests_properties(e2e.fragment-count.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()

# The real chain, once dem-run is built (mesh-gen | dem-run | fragment-count).
if(TARGET dem-run)
  add_test(NAME e2e.fragment-count.dem-run
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fragment_count.sh $<TARGET_FILE_DIR:fragment-count>
                   $<TARGET_FILE:fragment_count_make_run> ${CMAKE_CURRENT_BINARY_DIR}/work/fragment-count-dem-run dem-run)
  set_tests_properties(e2e.fragment-count.dem-run PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endif()
