# ctest driver: install the build into a fresh prefix, build the outside consumer
# against it with find_package, generate a table with the installed binary, run.
# -DBUILD_DIR=… -DSOURCE_DIR=… -DWORK_DIR=…
file(REMOVE_RECURSE "${WORK_DIR}")
include("${SOURCE_DIR}/cmake/slut_step.cmake")
step(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
step(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/consumer" -B "${WORK_DIR}/build" "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix")
step(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
step("${WORK_DIR}/prefix/bin/scatterlut" generate --out "${WORK_DIR}/tables" --format bin --n-u 128 --n-w 64)
step("${WORK_DIR}/build/consumer" "${WORK_DIR}/tables/airlight_F.slut")
# The GPU snippets, generated at build time, are installed beside the library.
foreach(snippet scatterlut_airlight.glsl scatterlut_airlight.hlsl scatterlut_nearlight.glsl scatterlut_nearlight.hlsl)
  if(NOT EXISTS "${WORK_DIR}/prefix/share/scatterlut/shaders/${snippet}")
    message(FATAL_ERROR "${snippet} is not installed in ${WORK_DIR}/prefix/share/scatterlut/shaders")
  endif()
endforeach()
# pkg-config sees the same library.
find_program(PKG_CONFIG pkg-config)
if(PKG_CONFIG)
  set(ENV{PKG_CONFIG_PATH} "${WORK_DIR}/prefix/lib/pkgconfig")
  execute_process(COMMAND ${PKG_CONFIG} --exists scatterlut RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config does not find scatterlut in ${WORK_DIR}/prefix")
  endif()
endif()
message(STATUS "outside consumer built and ran against the installed prefix")
