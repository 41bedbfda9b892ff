# mfp_add_library(NAME SOURCES file... [PUBLIC target...] [PRIVATE target...])
# The static library mfp_NAME and its alias mfp::NAME: headers included from the source
# root ("planner/x.h", "terrain/x.h", ...), linked to the targets given.
function(mfp_add_library name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "" "SOURCES;PUBLIC;PRIVATE")
  if(ARG_UNPARSED_ARGUMENTS OR NOT ARG_SOURCES)
    message(FATAL_ERROR "mfp_add_library(${name}): give SOURCES, then PUBLIC and PRIVATE targets "
                        "(unexpected: ${ARG_UNPARSED_ARGUMENTS})")
  endif()
  add_library(mfp_${name} ${ARG_SOURCES})
  add_library(mfp::${name} ALIAS mfp_${name})
  target_include_directories(mfp_${name} PUBLIC ${MFP_SOURCE_ROOT})
  if(ARG_PUBLIC)
    target_link_libraries(mfp_${name} PUBLIC ${ARG_PUBLIC})
  endif()
  if(ARG_PRIVATE)
    target_link_libraries(mfp_${name} PRIVATE ${ARG_PRIVATE})
  endif()
endfunction()
