# Writes the git sha of the source tree into a .cpp, with -dirty when what the binary is built from
# or reads at run time (micro/, shaders/, scenes/, presets/, the build files) differs from that commit,
# untracked files there included; results, scripts, tests and docs do not make a run's numbers dirty.
# Touches the .cpp only when the value changes so unchanged builds stay incremental.
execute_process(COMMAND git -C ${SRC} rev-parse --short=12 HEAD OUTPUT_VARIABLE sha
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR sha STREQUAL "")
  set(sha "unknown")
else()
  execute_process(COMMAND git -C ${SRC} status --porcelain --untracked-files=normal --
                          micro shaders scenes presets cmake CMakeLists.txt
                  OUTPUT_VARIABLE dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT dirty STREQUAL "")
    set(sha "${sha}-dirty")
  endif()
endif()
set(content "namespace oitbench { const char* git_sha() { return \"${sha}\"; } }\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
else()
  set(old "")
endif()
if(NOT old STREQUAL content)
  file(WRITE ${OUT} "${content}")
endif()
