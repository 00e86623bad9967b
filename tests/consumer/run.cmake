# ctest driver: install the build into a fresh prefix, generate a table with the installed
# binary, then move the prefix elsewhere (an install must not depend on where it was made)
# and build the outside consumer against the moved prefix twice: with find_package and with
# pkg-config. Both consumers load the table and compare with exact quadrature.
# -DBUILD_DIR=… -DSOURCE_DIR=… -DWORK_DIR=… -DCXX=… (the C++ compiler for the pkg-config build)
file(REMOVE_RECURSE "${WORK_DIR}")
include("${SOURCE_DIR}/cmake/slut_step.cmake")
set(installed "${WORK_DIR}/prefix")
set(moved "${WORK_DIR}/moved/prefix")
step(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${installed}")
step("${installed}/bin/scatterlut" generate --out "${WORK_DIR}/tables" --format bin --n-u 128 --n-w 64)
file(MAKE_DIRECTORY "${WORK_DIR}/moved")
file(RENAME "${installed}" "${moved}")

# find_package from the moved prefix.
step(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/consumer" -B "${WORK_DIR}/build" "-DCMAKE_PREFIX_PATH=${moved}")
step(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
step("${WORK_DIR}/build/consumer" "${WORK_DIR}/tables/airlight_F.slut")

# The GPU snippets, generated at build time, are installed beside the library.
foreach(snippet scatterlut_airlight.glsl scatterlut_airlight.hlsl scatterlut_nearlight.glsl scatterlut_nearlight.hlsl
                scatterlut_airlight_hg.glsl scatterlut_airlight_hg.hlsl scatterlut_airlight_hg.essl)
  if(NOT EXISTS "${moved}/share/scatterlut/shaders/${snippet}")
    message(FATAL_ERROR "${snippet} is not installed in ${moved}/share/scatterlut/shaders")
  endif()
endforeach()

# Only the runtime library and its headers: nothing of the tools' internals (the PNG encoder,
# the codecs' internal headers) is installed; the shared math headers are.
file(GLOB_RECURSE internal "${moved}/*png_writer*" "${moved}/*scatterlut_png*" "${moved}/*io_text.hpp"
     "${moved}/*io_binary_format.hpp" "${moved}/*io_exr_format.hpp")
if(internal)
  message(FATAL_ERROR "internal files are installed: ${internal}")
endif()
foreach(header slut_compat.h slut_axes.h slut_gauss_legendre.h slut_airlight.h slut_nearlight.h slut_nearlight_closed.h
               slut_nearlight_approx.h slut_nearlight_slab.h slut_nearlight_refraction.h slut_nearlight_frontend.h
               slut_nearlight_lanes.h slut_nearlight_march.h)
  if(NOT EXISTS "${moved}/include/scatterlut/kernels/${header}")
    message(FATAL_ERROR "${header} is not installed in ${moved}/include/scatterlut/kernels")
  endif()
endforeach()

# pkg-config from the moved prefix: the flags must name the moved prefix, never the old one.
find_program(PKG_CONFIG pkg-config)
if(NOT PKG_CONFIG)
  message(FATAL_ERROR "pkg-config not found (Debian: pkg-config; `make run` installs it)")
endif()
file(GLOB_RECURSE pc_files "${moved}/*/scatterlut.pc")
list(LENGTH pc_files pc_count)
if(NOT pc_count EQUAL 1)
  message(FATAL_ERROR "expected one scatterlut.pc under ${moved}, found: ${pc_files}")
endif()
get_filename_component(pc_dir "${pc_files}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
execute_process(COMMAND ${PKG_CONFIG} --static --cflags --libs scatterlut
                RESULT_VARIABLE rc OUTPUT_VARIABLE pc_flags ERROR_VARIABLE pc_err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config does not resolve scatterlut from ${pc_dir}: ${pc_err}")
endif()
string(FIND "${pc_flags}" "${installed}/" stale)
string(FIND "${pc_flags}" "-I${moved}/" fresh)
if(NOT stale EQUAL -1 OR fresh EQUAL -1)
  message(FATAL_ERROR "pkg-config flags do not follow the moved prefix ${moved}: ${pc_flags}")
endif()
separate_arguments(pc_args UNIX_COMMAND "${pc_flags}")
step(${CXX} -std=c++17 "${SOURCE_DIR}/tests/consumer/main.cpp" -o "${WORK_DIR}/consumer_pkgconfig" ${pc_args})
step("${WORK_DIR}/consumer_pkgconfig" "${WORK_DIR}/tables/airlight_F.slut")
message(STATUS "outside consumers (find_package, pkg-config) built and ran against a moved install")
