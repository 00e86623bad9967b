# ctest driver: install the build into a fresh prefix, generate a table with the installed
# binary, then move the prefix elsewhere (an install must not depend on where it was made)
# and build the outside consumer against the moved prefix three times: with find_package, with
# plain `pkg-config --cflags --libs` and with `pkg-config --static --cflags --libs`. Each
# consumer loads the table and compares with exact quadrature; with OpenEXR it also reads the
# table's EXR file with load_exr, so flags that leave out OpenEXR fail the link.
# -DBUILD_DIR=… -DSOURCE_DIR=… -DWORK_DIR=… -DCXX=… (the C++ compiler for the pkg-config builds)
# -DWITH_OPENEXR=ON|OFF (SCATTERLUT_WITH_OPENEXR of the build)
file(REMOVE_RECURSE "${WORK_DIR}")
include("${SOURCE_DIR}/cmake/slut_step.cmake")
set(installed "${WORK_DIR}/prefix")
set(moved "${WORK_DIR}/moved/prefix")
step(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${installed}")
set(tables "${WORK_DIR}/tables/airlight_F.slut")
set(format bin)
if(WITH_OPENEXR)
  list(APPEND tables "${WORK_DIR}/tables/airlight_F.exr")
  set(format both)
endif()
step("${installed}/bin/scatterlut" generate --out "${WORK_DIR}/tables" --format ${format} --n-u 128 --n-w 64)
file(MAKE_DIRECTORY "${WORK_DIR}/moved")
file(RENAME "${installed}" "${moved}")

# find_package from the moved prefix.
step(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/consumer" -B "${WORK_DIR}/build" "-DCMAKE_PREFIX_PATH=${moved}")
step(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
step("${WORK_DIR}/build/consumer" ${tables})

# The GPU snippets, generated at build time, are installed beside the library (and the WGSL
# ones, one file per tier, where the build generated them).
set(wgsl_snippets "")
if(WITH_WGSL)
  set(wgsl_snippets scatterlut_airlight.wgsl scatterlut_airlight_fast.wgsl scatterlut_airlight_accurate.wgsl
                    scatterlut_nearlight_hg_fast.wgsl scatterlut_surface_accurate.wgsl)
endif()
foreach(snippet scatterlut_airlight.glsl scatterlut_airlight.hlsl scatterlut_nearlight.glsl scatterlut_nearlight.hlsl
                scatterlut_airlight_hg.glsl scatterlut_airlight_hg.hlsl scatterlut_airlight_hg.essl ${wgsl_snippets})
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
foreach(form plain static)
  set(pc_options --cflags --libs)
  if(form STREQUAL "static")
    set(pc_options --static --cflags --libs)
  endif()
  string(REPLACE ";" " " pc_shown "${pc_options}")
  execute_process(COMMAND ${PKG_CONFIG} ${pc_options} scatterlut
                  RESULT_VARIABLE rc OUTPUT_VARIABLE pc_flags ERROR_VARIABLE pc_err OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config ${pc_shown} does not resolve scatterlut from ${pc_dir}: ${pc_err}")
  endif()
  string(FIND "${pc_flags}" "${installed}/" stale)
  string(FIND "${pc_flags}" "-I${moved}/" fresh_include)
  string(FIND "${pc_flags}" "-L${moved}/" fresh_lib)
  if(NOT stale EQUAL -1 OR fresh_include EQUAL -1 OR fresh_lib EQUAL -1)
    message(FATAL_ERROR "pkg-config ${pc_shown} flags do not follow the moved prefix ${moved}: ${pc_flags}")
  endif()
  message(STATUS "pkg-config ${pc_shown} scatterlut: ${pc_flags}")
  if(form STREQUAL "plain")
    # Exactly as a user writes it: the shell splits $(pkg-config --cflags --libs scatterlut).
    step(sh -c "\"$1\" -std=c++17 \"$2\" -o \"$3\" $(\"$4\" --cflags --libs scatterlut)" sh
         "${CXX}" "${SOURCE_DIR}/tests/consumer/main.cpp" "${WORK_DIR}/consumer_pkgconfig" "${PKG_CONFIG}")
  else()
    separate_arguments(pc_args UNIX_COMMAND "${pc_flags}")
    step(${CXX} -std=c++17 "${SOURCE_DIR}/tests/consumer/main.cpp" -o "${WORK_DIR}/consumer_pkgconfig_${form}"
         ${pc_args})
  endif()
endforeach()
step("${WORK_DIR}/consumer_pkgconfig" ${tables})
step("${WORK_DIR}/consumer_pkgconfig_static" ${tables})
message(STATUS "outside consumers (find_package, pkg-config plain and --static) built and ran against a moved install")
