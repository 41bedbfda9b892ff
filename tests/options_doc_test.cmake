# docs/options.md is what `mfp-plan --list-options --markdown` prints: fails when the
# option tables changed and the file was not regenerated.
# cmake -DMFP_PLAN=... -DDOC=docs/options.md -DOUT=build/.../options.md -P options_doc_test.cmake
execute_process(COMMAND ${MFP_PLAN} --list-options --markdown OUTPUT_FILE ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mfp-plan --list-options --markdown exited ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${DOC} RESULT_VARIABLE differs)
if(differs)
  message(FATAL_ERROR "${DOC} is stale: regenerate it with\n"
                      "  build/tools/mfp-plan --list-options --markdown > docs/options.md\n"
                      "(diff ${OUT} ${DOC} shows what changed)")
endif()
