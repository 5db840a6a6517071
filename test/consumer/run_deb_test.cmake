# The Debian packages of a build tree, made and consumed as a user of the .deb would:
#  1. cpack -G DEB makes the packages from BUILD_DIR (the Python module's too, if PYTHON is set:
#     the interpreter it was built for);
#  2. their control data must name the Debian packages they need, and the library's must hold
#     the library, the headers, the CMake package and the pkg-config file, the module's its
#     package in Debian's Python folder;
#  3. they are unpacked (dpkg-deb -x: the files an install puts in /usr, under WORK_DIR/root);
#  4. the consumer (consumer/) is built against it with CMake (find_package), and scene.cpp
#     once more with nothing but pkg-config's flags; both run;
#  5. the interpreter imports the unpacked module (which finds the library by its RPATH) and
#     queries a shape.
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

# 1. The packages.
run(${CPACK} -G DEB --config ${BUILD_DIR}/CPackConfig.cmake -B ${WORK_DIR}/deb)
file(GLOB debs ${WORK_DIR}/deb/libfcl-superellipsoid-dev_*.deb)
file(GLOB python_debs ${WORK_DIR}/deb/python3-fcl-superellipsoid_*.deb)
list(LENGTH debs count)
list(LENGTH python_debs python_count)
set(expected_python 0)
if(PYTHON)
  set(expected_python 1)
endif()
if(NOT count EQUAL 1 OR NOT python_count EQUAL expected_python)
  file(GLOB all ${WORK_DIR}/deb/*.deb)
  message(FATAL_ERROR "expected one library package and ${expected_python} Python package(s) in "
                      "${WORK_DIR}/deb, found: ${all}")
endif()
message(STATUS "packages: ${debs} ${python_debs}")

# 2. What they say and what they hold.
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
string(FIND "${contents}" "dist-packages" python_in_dev)
if(NOT python_in_dev EQUAL -1)
  message(FATAL_ERROR "the library's package holds Python files:\n${contents}")
endif()
if(PYTHON)
  run(dpkg-deb --field ${python_debs} Package Depends)
  foreach(needle python3-fcl-superellipsoid "libfcl-superellipsoid-dev (=" python3-numpy
          "python3 (>=")
    expect("${run_output}" "${needle}" "control of the Python package")
  endforeach()
  run(dpkg-deb --contents ${python_debs})
  foreach(file __init__.py __init__.pyi py.typed _core.cpython)
    expect("${run_output}" "./usr/lib/python3/dist-packages/fcl_superellipsoid/${file}"
           "contents of the Python package")
  endforeach()
endif()

# 3. Unpacked.
foreach(deb ${debs} ${python_debs})
  run(dpkg-deb -x ${deb} ${root})
endforeach()
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

# 5. The Python module, as the interpreter finds it in /usr/lib/python3/dist-packages; no
#    LD_LIBRARY_PATH, so the library comes through the module's RPATH.
if(PYTHON)
  set(ENV{LD_LIBRARY_PATH} "")
  set(ENV{PYTHONPATH} "${root}/usr/lib/python3/dist-packages")
  # (Python statements on lines of their own: a ";" would split the argument in CMake.)
  run(${PYTHON} -c "import fcl_superellipsoid as f
s = f.Superellipsoid((1, 1, 1), (1, 1))
assert f.__file__.startswith('${root}'), f.__file__
print(s.signed_distance([[3, 0, 0]])[0])")
  expect("${run_output}" "2.0" "Python import")
  message(STATUS "Python consumer: ${run_output}")
endif()
