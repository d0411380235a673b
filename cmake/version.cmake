# Writes the git sha and the version of the source tree into a .cpp, with -dirty when what the binary
# is built from or reads at run time (micro/, shaders/, scenes/, presets/, the build files) differs from
# that commit, untracked files there included; results, scripts, tests and docs do not make a run's
# numbers dirty. The version is `git describe` against the v* tags (v0.1.0-123-gSHA) or, where there is
# no such tag, the project version and the sha (0.1.0-gSHA); the same -dirty rule marks both.
# Touches the .cpp only when a value changes so unchanged builds stay incremental.
# Inputs: SRC (the source tree), OUT (the .cpp), PROJECT_VERSION.
execute_process(COMMAND git -C ${SRC} rev-parse --short=12 HEAD OUTPUT_VARIABLE sha
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR sha STREQUAL "")
  set(sha "unknown")
  set(version "${PROJECT_VERSION}-unknown")
else()
  execute_process(COMMAND git -C ${SRC} describe --tags --long --match "v[0-9]*" --abbrev=12 HEAD
                  OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR version STREQUAL "")
    set(version "${PROJECT_VERSION}-g${sha}")
  endif()
  execute_process(COMMAND git -C ${SRC} status --porcelain --untracked-files=normal --
                          micro shaders scenes presets cmake CMakeLists.txt
                  OUTPUT_VARIABLE dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT dirty STREQUAL "")
    set(sha "${sha}-dirty")
    set(version "${version}-dirty")
  endif()
endif()
string(CONCAT content "namespace oitbench {\nconst char* git_sha() { return \"${sha}\"; }\n"
       "const char* version_string() { return \"${version}\"; }\n}  // namespace oitbench\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
else()
  set(old "")
endif()
if(NOT old STREQUAL content)
  file(WRITE ${OUT} "${content}")
endif()
