# Writes the man pages and the bash completion of the tool into DIR, from the tool itself (`trionet --man`,
# `trionet --completion bash`: written from its command and option tables):
#   cmake -DTOOL=build/src/trionet -DDIR=build/manual -P cmake/write_manual.cmake
# DIR/man1/<page>.1 for every page `trionet --man` names, DIR/bash-completion/trionet.
foreach(variable TOOL DIR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "write_manual.cmake needs -D${variable}=...")
  endif()
endforeach()

function(run_tool output)
  execute_process(COMMAND ${TOOL} ${ARGN} OUTPUT_FILE ${output} RESULT_VARIABLE status ERROR_VARIABLE error)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${TOOL} ${ARGN} failed (${status}): ${error}")
  endif()
endfunction()

file(MAKE_DIRECTORY ${DIR}/man1 ${DIR}/bash-completion)
run_tool(${DIR}/pages.txt --man)
file(STRINGS ${DIR}/pages.txt pages)
if(NOT pages)
  message(FATAL_ERROR "${TOOL} --man named no page")
endif()
foreach(page ${pages})
  run_tool(${DIR}/man1/${page}.1 --man ${page})
endforeach()
run_tool(${DIR}/bash-completion/trionet --completion bash)
