# Run by ctest: install, configure and build a host sample (SAMPLE, default embed_minimal) against the
# installed package, run it, check its output. physics_only also checks what its link pulls in.
# With PKG_CONFIG_MODULE the host is built without CMake: one compiler command (CC for a .c sample, CXX
# for C++20) with the flags of `pkg-config --cflags --libs PKG_CONFIG_MODULE` from the installed .pc files.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
if(NOT DEFINED SAMPLE)
  set(SAMPLE embed_minimal)
endif()
set(host ${WORK_DIR}/host)

# What every install holds: the generated version.h of this version, and render.h only with an exported
# supermodal::render (a host including it must be able to link what it declares).
file(STRINGS ${prefix}/include/supermodal/version.h version_line REGEX "#define SM_VERSION_STRING ")
if(NOT version_line STREQUAL "#define SM_VERSION_STRING \"${VERSION}\"")
  message(FATAL_ERROR "installed supermodal/version.h: '${version_line}', expected version ${VERSION}")
endif()
# The scene schema, as in the source tree.
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${SOURCE_DIR}/docs/scene.schema.json
  ${prefix}/share/supermodal/scene.schema.json RESULT_VARIABLE schema_differs)
if(NOT schema_differs EQUAL 0)
  message(FATAL_ERROR "share/supermodal/scene.schema.json is not installed, or differs from docs/")
endif()
file(READ ${prefix}/${LIBDIR}/cmake/supermodal/supermodalTargets.cmake targets)
string(FIND "${targets}" "add_library(supermodal::render " render_exported)
if(EXISTS ${prefix}/include/supermodal/render.h AND render_exported EQUAL -1)
  message(FATAL_ERROR "render.h is installed but supermodal::render is not exported")
endif()

if(DEFINED PKG_CONFIG_MODULE)
  # The host's own command line: pkg-config's flags and a run path to the installed libraries (for a
  # shared install; pkg-config leaves run paths to the host).
  set(ENV{PKG_CONFIG_PATH} ${prefix}/${LIBDIR}/pkgconfig)
  find_program(PKG_CONFIG pkg-config REQUIRED)
  run(${PKG_CONFIG} --modversion ${PKG_CONFIG_MODULE})
  if(NOT last_output STREQUAL "${VERSION}\n")
    message(FATAL_ERROR "pkg-config --modversion ${PKG_CONFIG_MODULE}: '${last_output}', expected ${VERSION}")
  endif()
  run(${PKG_CONFIG} --cflags --libs ${PKG_CONFIG_MODULE})
  separate_arguments(flags UNIX_COMMAND "${last_output}")
  run(${PKG_CONFIG} --variable=libdir ${PKG_CONFIG_MODULE})
  string(STRIP "${last_output}" libdir)
  file(GLOB source ${SOURCE_DIR}/samples/${SAMPLE}/main.c ${SOURCE_DIR}/samples/${SAMPLE}/main.cpp)
  if(source MATCHES "[.]c$")
    set(compile ${C_COMPILER} -std=c11)
  else()
    set(compile ${CXX_COMPILER} -std=c++20)
  endif()
  file(MAKE_DIRECTORY ${host})
  set(command ${compile} -Wall -Wextra -Werror ${source} -o ${SAMPLE} ${flags} -Wl,-rpath,${libdir})
  execute_process(COMMAND ${command} WORKING_DIRECTORY ${host} RESULT_VARIABLE rc OUTPUT_VARIABLE out
    ERROR_VARIABLE out)
  list(JOIN command " " build_output)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${build_output}\n${out}")
  endif()
else()
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/samples/${SAMPLE} -B ${host} -G ${GENERATOR}
      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${host} --verbose) # --verbose: the link command, for physics_only
  set(build_output "${last_output}")
endif()

if(SAMPLE STREQUAL "c_minimal") # the C host: its own output checks
  run(${CMAKE_COMMAND} -DPROGRAM=${host}/c_minimal -DSCENE=${SOURCE_DIR}/samples/demo.json
      -P ${SOURCE_DIR}/tests/capi/run_c_minimal.cmake)
  return()
endif()

if(SAMPLE STREQUAL "embed_in_code") # bodies and joints made in code, drawn between steps: checks itself
  run(${host}/embed_in_code)
  if(NOT last_output MATCHES "\nok\n?$")
    message(FATAL_ERROR "unexpected host output:\n${last_output}")
  endif()
  message(STATUS "host output:\n${last_output}")
  return()
endif()

if(SAMPLE STREQUAL "render_minimal")
  run(${host}/render_minimal ${SOURCE_DIR}/tests/tools/scenes/projectile.json ${WORK_DIR}/frame.png)
  if(NOT last_output MATCHES "wrote .*frame.png: 160x120 on " OR NOT EXISTS ${WORK_DIR}/frame.png)
    message(FATAL_ERROR "unexpected host output:\n${last_output}")
  endif()
  message(STATUS "host output:\n${last_output}")
  return()
endif()

if(SAMPLE STREQUAL "physics_only")
  # The link must hold the engine and nothing of assets (JSON, assimp), the C API or render (EGL, GLES),
  # static or shared: first the linker's command line, then every library the program loads.
  set(forbidden "assimp|EGL|libGL|json|supermodal_assets|supermodal_c[.]|supermodal_render")
  string(REGEX MATCH "[^\n]* -o physics_only[^\n]*" link_line "${build_output}")
  if(NOT link_line MATCHES "libsupermodal[.]|-lsupermodal( |$)")
    message(FATAL_ERROR "no link command naming libsupermodal in the build output:\n${build_output}")
  endif()
  if(link_line MATCHES "${forbidden}")
    message(FATAL_ERROR "physics_only's link pulls in '${CMAKE_MATCH_0}':\n${link_line}")
  endif()
  find_program(LDD ldd REQUIRED)
  run(${LDD} ${host}/physics_only)
  if(last_output MATCHES "${forbidden}")
    message(FATAL_ERROR "physics_only loads '${CMAKE_MATCH_0}':\n${last_output}")
  endif()
  message(STATUS "link:\n${link_line}\nloads:\n${last_output}")
  run(${host}/physics_only)
  # The ball (radius 0.5 m) dropped from 1 m rests on the ground after two seconds.
  if(NOT last_output MATCHES "ball position 0[.]000000 0[.](49|50)[0-9]* 0[.]000000\nsteps 1000 hash [0-9a-f]+")
    message(FATAL_ERROR "unexpected host output:\n${last_output}")
  endif()
  message(STATUS "host output:\n${last_output}")
  return()
endif()

run(${host}/embed_minimal ${SOURCE_DIR}/tests/tools/scenes/projectile.json)
if(NOT last_output MATCHES "ball position (2\\.99|3\\.00)")
  message(FATAL_ERROR "unexpected host output:\n${last_output}")
endif()
message(STATUS "host output:\n${last_output}")
