# Installs softstep from BUILD_DIR into WORK_DIR/prefix, extracts the README's embedding
# example into a consumer project, builds it and reference_consumer.cpp (the accuracy
# references across the ABI) against the installed tree and runs both.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/project)

execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()

file(READ ${SOURCE_DIR}/README.md readme)
string(REGEX MATCH "<!-- embed-example-begin -->[^`]*```cpp\n(.*)```[^`]*<!-- embed-example-end -->" found "${readme}")
if(NOT found)
  message(FATAL_ERROR "README.md has no embedding example between the embed-example markers")
endif()
file(WRITE ${WORK_DIR}/project/main.cpp "${CMAKE_MATCH_1}")
file(COPY ${SOURCE_DIR}/tests/consumer/CMakeLists.txt ${SOURCE_DIR}/tests/consumer/reference_consumer.cpp
     DESTINATION ${WORK_DIR}/project)

execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/project -B ${WORK_DIR}/build
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                        -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
                        "-DCMAKE_EXE_LINKER_FLAGS=${LINK_FLAGS}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the consumer against the installed softstep failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer failed")
endif()
foreach(program consumer reference_consumer)
  execute_process(COMMAND ${WORK_DIR}/build/${program} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the ${program} exited with ${rc}")
  endif()
endforeach()
