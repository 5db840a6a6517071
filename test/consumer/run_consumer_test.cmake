# Consumes the installed package from an out-of-tree project (test/consumer/).
#   BUILD_DIR set:   install that build tree (the one under test) into a temporary prefix.
#   BUILD_DIR empty: configure the library afresh with BUILD_SHARED_LIBS=${BUILD_SHARED} (so the
#                    suite checks the other library kind too), made of the compiled objects of
#                    the build tree OBJECTS_FROM (src/CMakeLists.txt → FSE_OBJECTS_FROM: the
#                    objects are alike for both kinds), or compiled afresh without OBJECTS_FROM
#                    (Debug, -O0: how the kind is packaged and linked, not its speed); only what
#                    is installed (no tests, benchmark, scene runner, fit or module); then
#                    install it.
# Then configure, build and run the consumer against the prefix.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()
if(NOT BUILD_DIR)
  set(BUILD_DIR ${WORK_DIR}/lib-build)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR} -G ${GENERATOR}
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DBUILD_SHARED_LIBS=${BUILD_SHARED}
      -DFSE_BUILD_TESTS=OFF -DFSE_BUILD_BENCH=OFF -DFSE_BUILD_SIM=OFF -DFSE_BUILD_FIT=OFF
      -DFSE_BUILD_PYTHON=OFF -DFSE_OBJECTS_FROM=${OBJECTS_FROM})
  run(${CMAKE_COMMAND} --build ${BUILD_DIR} --parallel 2)
endif()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/test/consumer -B ${WORK_DIR}/consumer-build
    -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${prefix} "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/consumer-build)
set(ENV{LD_LIBRARY_PATH} "${prefix}/lib:${prefix}/lib64:$ENV{LD_LIBRARY_PATH}")
run(${WORK_DIR}/consumer-build/consumer)
run(${WORK_DIR}/consumer-build/scene)
run(${WORK_DIR}/consumer-build/plain_calls interposed)
file(READ ${WORK_DIR}/consumer-build/interpose_kind.txt kind)
if(kind STREQUAL "STATIC_LIBRARY")
  run(${WORK_DIR}/consumer-build/plain_calls_fcl_first interposed)
else()
  run(${WORK_DIR}/consumer-build/plain_calls_fcl_first libfcl)
endif()

# The Python module, if this tree built it: imported from the prefix's Python folder.
if(PYTHON AND PYTHON_DIR)
  set(ENV{LD_LIBRARY_PATH} "")
  set(ENV{PYTHONPATH} "${prefix}/${PYTHON_DIR}")
  # (Python statements on lines of their own: a ";" would split the argument in CMake.)
  run(${PYTHON} -c "import fcl_superellipsoid as f
assert f.__file__.startswith('${prefix}'), f.__file__
assert f.Superellipsoid((1, 1, 1), (1, 1)).signed_distance([3, 0, 0]) == 2.0
print('Python consumer: imported from', f.__file__)")
endif()
