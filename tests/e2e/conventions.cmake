# The conventions of every tool (included by tests/e2e/CMakeLists.txt): one case per tool and mesh-gen
# subcommand (--help with an example, --version, bad options, -q, --config FILE taking effect), a case
# that fails when a tool or subcommand is missing from this list, and the provenance of PNG, SVG, CSV
# and XDMF outputs.
set(FRACTURE_CONVENTION_COMMANDS mesh-gen.voronoi mesh-gen.triangular mesh-gen.check dem-run rubber-run observables
    fragment-count powerlaw-fit wave-speed render h5-xdmf)
foreach(case ${FRACTURE_CONVENTION_COMMANDS} every-tool provenance)
  add_test(NAME e2e.conventions.${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/conventions.sh ${PROJECT_SOURCE_DIR} $<TARGET_FILE_DIR:mesh-gen>
                   ${CMAKE_CURRENT_BINARY_DIR}/work/conventions-${case} ${case} ${FRACTURE_CONVENTION_COMMANDS})
  set_tests_properties(e2e.conventions.${case} PROPERTIES LABELS e2e ENVIRONMENT "${FRACTURE_TEST_ENV}")
endforeach()
