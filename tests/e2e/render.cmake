# End-to-end cases of render and h5-xdmf (included by tests/e2e/CMakeLists.txt): help and version,
# pictures of a short dem-run explosion (PNG size and magic bytes, SVG with a path per cell, every
# colouring, standard output, fragments), a frame sequence, a rubber run, XDMF sidecars whose references
# name existing datasets with the right dimensions, and refusals of bad input (exit 2, nothing left).
foreach(case help pictures movie rubber xdmf bad-input)
  add_test(NAME e2e.render.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/render.sh $<TARGET_FILE_DIR:render> ${PROJECT_SOURCE_DIR}/data/scenes
                   ${CMAKE_CURRENT_BINARY_DIR}/work/render-${case} ${case})
  set_tests_properties(e2e.render.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()
