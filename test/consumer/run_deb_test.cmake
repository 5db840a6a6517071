# The Debian package of a build tree, made and consumed as a user of the .deb would:
#  1. cpack -G DEB makes the package from BUILD_DIR;
#  2. its control data must name the Debian packages it needs, and it must hold the library,
#     the headers, the CMake package and the pkg-config file;
#  3. it is unpacked (dpkg-deb -x: the files an install puts in /usr, under WORK_DIR/root);
#  4. the consumer (consumer/) is built against it with CMake (find_package), and scene.cpp
#     once more with nothing but pkg-config's flags; both run.
# (Installing it for real is `apt-get install ./libfcl-superellipsoid-dev_*.deb`; a test does not
# change the machine's /usr.)
file(REMOVE_RECURSE ${WORK_DIR})
set(root ${WORK_DIR}/root)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()
function(expect haystack needle what)
  string(FIND "${haystack}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the package ${what}: '${needle}' not found in\n${haystack}")
  endif()
endfunction()

# 1. The package.
run(${CPACK} -G DEB --config ${BUILD_DIR}/CPackConfig.cmake -B ${WORK_DIR}/deb)
file(GLOB debs ${WORK_DIR}/deb/*.deb)
list(LENGTH debs count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "expected one .deb in ${WORK_DIR}/deb, found: ${debs}")
endif()
message(STATUS "package: ${debs}")

# 2. What it says and what it holds.
run(dpkg-deb --field ${debs} Package Depends)
expect("${run_output}" "libfcl-superellipsoid-dev" "control: name")
foreach(dependency libfcl-dev libeigen3-dev libtbb-dev libhwy-dev)
  expect("${run_output}" "${dependency}" "control: Depends")
endforeach()
run(dpkg-deb --contents ${debs})
set(contents "${run_output}")
foreach(file include/fcl_superellipsoid/superellipsoid.h include/fcl_superellipsoid/export.h
        fcl_superellipsoidConfig.cmake fcl_superellipsoidTargets.cmake
        pkgconfig/fcl_superellipsoid.pc libfcl_superellipsoid libfcl_superellipsoid_interpose
        include/fcl_superellipsoid/interpose.h)
  expect("${contents}" "${file}" "contents")
endforeach()

# 3. Unpacked.
run(dpkg-deb -x ${debs} ${root})
file(GLOB_RECURSE pc_files ${root}/*/fcl_superellipsoid.pc)
get_filename_component(pc_dir "${pc_files}" DIRECTORY)
get_filename_component(lib_dir "${pc_dir}" DIRECTORY)
set(ENV{LD_LIBRARY_PATH} "${lib_dir}:$ENV{LD_LIBRARY_PATH}")

# 4a. Through CMake.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/test/consumer -B ${WORK_DIR}/cmake-consumer
    -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${root}/usr "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/cmake-consumer)
run(${WORK_DIR}/cmake-consumer/consumer)
run(${WORK_DIR}/cmake-consumer/scene)
message(STATUS "CMake consumer: ${run_output}")
run(${WORK_DIR}/cmake-consumer/plain_calls interposed)

# 4b. Through pkg-config alone: its flags must find the unpacked headers and library.
set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
run(pkg-config --cflags --libs fcl_superellipsoid)
string(STRIP "${run_output}" flags)
expect("${flags}" "${root}" "pkg-config flags (must point into the unpacked tree)")
separate_arguments(flags UNIX_COMMAND "${flags}")
separate_arguments(consumer_flags UNIX_COMMAND "${CONSUMER_FLAGS}")
# FCL's own pkg-config file adds -std=c++11: the standard goes after the flags (docs/usage.md).
run(c++ -O1 ${consumer_flags} ${SOURCE_DIR}/test/consumer/scene.cpp ${flags} -std=c++17
    -o ${WORK_DIR}/scene-pkg-config)
run(${WORK_DIR}/scene-pkg-config)
message(STATUS "pkg-config consumer: ${run_output}")
