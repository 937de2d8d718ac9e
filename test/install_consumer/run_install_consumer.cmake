# Installs the package from BUILD_DIR into PREFIX, then configures, builds and
# runs the consumer project SOURCE_DIR against it (in WORK_DIR). Any failing
# step fails the test with that step's output.
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install_consumer: ${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "install_consumer: ${what}: ok")
endfunction()

file(REMOVE_RECURSE ${PREFIX} ${WORK_DIR})
run_step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
if(NOT EXISTS ${PREFIX}/include/CGAL/Blended_shape.h)
  message(FATAL_ERROR "install_consumer: the headers were not installed under ${PREFIX}/include")
endif()
run_step("configure the consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}
         -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${PREFIX})
run_step("build the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR})
run_step("run the consumer" ${WORK_DIR}/consumer)
