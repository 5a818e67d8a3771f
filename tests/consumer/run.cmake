# Installs trionet into a scratch prefix, then configures, builds and runs an outside consumer
# that finds it with find_package(trionet CONFIG REQUIRED).
file(REMOVE_RECURSE ${WORK_DIR})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}")
  endif()
endfunction()
step(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/lib -DCMAKE_CXX_COMPILER=${CXX}
     -DTRIONET_BUILD_TESTS=OFF -DTRIONET_BUILD_TOOLS=OFF -DTRIONET_BUILD_EXAMPLES=OFF -DTRIONET_BUILD_HOST=ON
     -DCMAKE_INSTALL_PREFIX=${WORK_DIR}/prefix)
step(${CMAKE_COMMAND} --build ${WORK_DIR}/lib)
step(${CMAKE_COMMAND} --install ${WORK_DIR}/lib)
step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/app -DCMAKE_CXX_COMPILER=${CXX}
     -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
step(${CMAKE_COMMAND} --build ${WORK_DIR}/app)
step(${WORK_DIR}/app/consumer)
step(${WORK_DIR}/app/host_consumer)
