# Compiles SOURCE with CXX and the library's include directory INCLUDE and passes only if the compiler
# refuses it with an error that contains EXPECT: a configuration the library must reject at compile time.
execute_process(COMMAND ${CXX} -std=c++17 -fsyntax-only -I${INCLUDE} ${SOURCE}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(result EQUAL 0)
  message(FATAL_ERROR "${SOURCE} compiled, but it must not")
endif()
string(FIND "${out}${err}" "${EXPECT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${SOURCE} failed to compile, but not with \"${EXPECT}\":\n${err}")
endif()
message(STATUS "refused as it must be: ${EXPECT}")
