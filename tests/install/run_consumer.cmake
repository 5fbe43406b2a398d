# Installs the build tree BUILD into WORK/prefix, builds the consumer project against it and runs
# its programs. The installed data must be found without FASTRON_DATA_DIR.
set(prefix ${WORK}/prefix)
file(REMOVE_RECURSE ${WORK})
unset(ENV{FASTRON_DATA_DIR})

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "failed (${code}): ${ARGN}\n${out}\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
run(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/build -G Ninja -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix} -DFASTRON_EXAMPLES=${EXAMPLES})
run(${CMAKE_COMMAND} --build ${WORK}/build)

run(${WORK}/build/data_directory)
if(NOT output MATCHES "^${prefix}/share/fastron\n.*caught: .*not finite")
  message(FATAL_ERROR "expected the installed data folder and a caught InvalidArgument:\n${output}")
endif()
run(${WORK}/build/planning)
message(STATUS "planning: ${output}")
run(${WORK}/build/quickstart_static)
# The shared libraries are what the programs use, from the prefix.
run(ldd ${WORK}/build/planning)
if(NOT output MATCHES "${prefix}/lib/libfastron_planning.so")
  message(FATAL_ERROR "the program does not load the installed libfastron_planning.so:\n${output}")
endif()
# The installed command finds its robots by itself too.
run(${prefix}/bin/fastron robots)
if(NOT output MATCHES "baxter")
  message(FATAL_ERROR "the installed fastron command lists no shipped robot:\n${output}")
endif()
