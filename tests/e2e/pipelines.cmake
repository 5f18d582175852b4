# End-to-end cases of the experiment pipelines (included by tests/e2e/CMakeLists.txt): a miniature of every
# experiment (MINI=1) through its real Make target in Makefile.analysis, with the tools of this build;
# each table must exist with its columns and finite values, each picture must be a PNG.
foreach(experiment demo elastic-moduli compression explosion impact rubber-crack accuracy-cost)
  add_test(NAME e2e.pipelines.${experiment}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/pipelines.sh ${PROJECT_SOURCE_DIR} ${CMAKE_BINARY_DIR}
                   ${CMAKE_CURRENT_BINARY_DIR}/work/pipelines-${experiment} ${experiment})
  set_tests_properties(e2e.pipelines.${experiment} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}"
                       TIMEOUT 300)
endforeach()
