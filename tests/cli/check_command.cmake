# Runs a command and checks what a user would see.
#   CMD            the command, arguments separated by '|'
#   EXPECT_CODE    expected exit code
#   EXPECT_REGEX   optional regexes (separated by '|||') that stdout + stderr must match
#   EXPECT_STDERR_ONE_LINE  if set, stderr must be exactly one line
#   EXPECT_FILES   optional files (separated by '|') that must exist and be non-empty afterwards
string(REPLACE "|" ";" command "${CMD}")
execute_process(COMMAND ${command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
if(NOT code EQUAL EXPECT_CODE)
  message(FATAL_ERROR "exit code ${code}, expected ${EXPECT_CODE}\n--- output ---\n${all}")
endif()
if(DEFINED EXPECT_REGEX)
  string(REPLACE "|||" ";" regexes "${EXPECT_REGEX}")
  foreach(re IN LISTS regexes)
    if(NOT all MATCHES "${re}")
      message(FATAL_ERROR "output does not match '${re}'\n--- output ---\n${all}")
    endif()
  endforeach()
endif()
if(EXPECT_STDERR_ONE_LINE AND NOT err MATCHES "^[^\n]+\n$")
  message(FATAL_ERROR "stderr is not exactly one line:\n${err}")
endif()
if(DEFINED EXPECT_FILES)
  string(REPLACE "|" ";" files "${EXPECT_FILES}")
  foreach(f IN LISTS files)
    file(SIZE "${f}" size)
    if(NOT EXISTS "${f}" OR size EQUAL 0)
      message(FATAL_ERROR "missing or empty: ${f}")
    endif()
  endforeach()
endif()
