# The out-of-tree consumer (examples/consumer) against an installed strahl, in a fresh prefix:
# install, find_package(strahl) → build → run, and the same program built with pkg-config's flags;
# each must write exactly the CLI's image of the lecture scene (the same bytes of a .pfm).
#   cmake -DMODE=static|shared -DBUILD=<strahl build> -DSOURCE=<strahl source> -DWORK=<scratch dir>
#         -DCLI=<strahl CLI for the reference image> -DCXX=<compiler> -P consumer_test.cmake
# static: installs BUILD (the main build: libstrahl.a, programs, docs).
# shared: configures SOURCE anew with -DBUILD_SHARED_LIBS=ON (library only, -O0 to keep the
#         test short: it checks the packaging, not the speed) and installs its library component.
cmake_minimum_required(VERSION 3.25)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "failed (${rc}): ${command}\n${out}")
  endif()
endfunction()
macro(fail message)
  message(FATAL_ERROR "${message}")
endmacro()

file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")

if(MODE STREQUAL "static")
  run(${CMAKE_COMMAND} --install "${BUILD}" --prefix "${prefix}")
  file(GLOB lib "${prefix}/lib*/libstrahl.a" "${prefix}/lib*/*/libstrahl.a")
  if(NOT lib)
    fail("no libstrahl.a in ${prefix}")
  endif()
  if(NOT EXISTS "${prefix}/bin/strahl" OR NOT EXISTS "${prefix}/share/doc/strahl/library.md")
    fail("the programs or the docs are not installed")
  endif()
  set(CLI "${prefix}/bin/strahl")  # the installed program renders the reference
elseif(MODE STREQUAL "shared")
  load_cache("${BUILD}" READ_WITH_PREFIX main_ CMAKE_CXX_COMPILER_LAUNCHER STRAHL_NATIVE)
  run(${CMAKE_COMMAND} -S "${SOURCE}" -B "${WORK}/strahl-shared" -DBUILD_SHARED_LIBS=ON
      -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O0" -DSTRAHL_BUILD_TESTS=OFF -DSTRAHL_BUILD_EXTRAS=OFF -DSTRAHL_CUDA=OFF
      -DSTRAHL_NATIVE=${main_STRAHL_NATIVE} "-DCMAKE_CXX_COMPILER=${CXX}"
      "-DCMAKE_CXX_COMPILER_LAUNCHER=${main_CMAKE_CXX_COMPILER_LAUNCHER}")
  run(${CMAKE_COMMAND} --build "${WORK}/strahl-shared" --target strahl)
  run(${CMAKE_COMMAND} --install "${WORK}/strahl-shared" --prefix "${prefix}" --component library)
  file(GLOB lib "${prefix}/lib*/libstrahl.so.*" "${prefix}/lib*/*/libstrahl.so.*")
  file(GLOB static_lib "${prefix}/lib*/libstrahl.a" "${prefix}/lib*/*/libstrahl.a")
  if(NOT lib OR static_lib)
    fail("a shared build must install libstrahl.so and no libstrahl.a: '${lib}' '${static_lib}'")
  endif()
else()
  message(FATAL_ERROR "MODE must be static or shared")
endif()

# Only the public headers are installed: strahl.h, what it includes, the generated version.h.
foreach(public strahl.h version.h scene/scene.h)
  if(NOT EXISTS "${prefix}/include/strahl/${public}")
    fail("strahl/${public} is not installed")
  endif()
endforeach()
foreach(internal render/whitted.h render/adaptive.h scene/obj_loader.h scene/validate.h)
  if(EXISTS "${prefix}/include/strahl/${internal}")
    fail("the internal header strahl/${internal} was installed")
  endif()
endforeach()

run("${CLI}" -q --width 800 --height 450 -o "${WORK}/cli.pfm")

# find_package(strahl 0.1 REQUIRED) and strahl::strahl.
run(${CMAKE_COMMAND} -S "${SOURCE}/examples/consumer" -B "${WORK}/consumer" "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_COMPILER=${CXX}" -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build "${WORK}/consumer")
run("${WORK}/consumer/lecture" "${WORK}/consumer.pfm")
run(${CMAKE_COMMAND} -E compare_files "${WORK}/cli.pfm" "${WORK}/consumer.pfm")
if(MODE STREQUAL "shared")  # it really runs on the installed libstrahl.so
  file(GET_RUNTIME_DEPENDENCIES EXECUTABLES "${WORK}/consumer/lecture" RESOLVED_DEPENDENCIES_VAR deps)
  list(FILTER deps INCLUDE REGEX "libstrahl")
  list(GET lib 0 lib)
  file(REAL_PATH "${lib}" lib_real)
  foreach(dep IN LISTS deps)
    file(REAL_PATH "${dep}" dep_real)
  endforeach()
  if(NOT deps OR NOT dep_real STREQUAL lib_real)
    fail("the consumer loads '${deps}', not the installed ${lib}")
  endif()
endif()

# pkg-config: the same program with `pkg-config --cflags --libs [--static] strahl`.
set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
set(static_flag "")
if(MODE STREQUAL "static")
  set(static_flag --static)
endif()
execute_process(COMMAND pkg-config --cflags --libs ${static_flag} strahl RESULT_VARIABLE rc OUTPUT_VARIABLE flags
                ERROR_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  fail("pkg-config --cflags --libs strahl: ${flags}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run("${CXX}" -O1 "${SOURCE}/examples/consumer/lecture.cpp" -o "${WORK}/lecture-pc" ${flags} "-Wl,-rpath,${prefix}/lib")
run("${WORK}/lecture-pc" "${WORK}/pkg-config.pfm")
run(${CMAKE_COMMAND} -E compare_files "${WORK}/cli.pfm" "${WORK}/pkg-config.pfm")
message(STATUS "${MODE}: find_package and pkg-config builds write the CLI's image")
