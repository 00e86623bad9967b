# Assembles one GPU sampling snippet (GLSL, GLSL ES 3.00 for WebGL2, or HLSL) from its one
# source: the language-neutral body tables/shaders/src/<name>.slsl, the language prelude
# (prelude.glsl / prelude.essl / prelude.hlsl: texture access, infinity, constant arrays,
# ES precision), the shared
# float math and C-subset layer (common.slsl) and, copied verbatim into that layer, the
# regions between SLUT_SHADER_BEGIN and SLUT_SHADER_END of the kernels/ headers: the
# axis maps and closed forms the generator and the C++ sampler compile, compiled a third
# time as GLSL/HLSL (docs/SHADERS.md, "One source"). Their block comments are dropped
# (the derivations stay in the headers; the snippets stay ASCII).
# Usage: cmake -DLANG=glsl|hlsl|essl -DNAME=airlight -DSRC_DIR=tables/shaders/src
#              -DKERNELS_DIR=kernels -DHEADERS="slut_axes.h|slut_nearlight.h" -DOUT=file
#              -P assemble_shaders.cmake
cmake_policy(VERSION 3.20)
foreach(var LANG NAME SRC_DIR KERNELS_DIR HEADERS OUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "assemble_shaders.cmake: -D${var}=... is required")
  endif()
endforeach()
if(LANG STREQUAL "glsl")
  set(lang_name "GLSL")
elseif(LANG STREQUAL "hlsl")
  set(lang_name "HLSL")
elseif(LANG STREQUAL "essl")
  set(lang_name "GLSL ES 3.00 (WebGL2)")
else()
  message(FATAL_ERROR "assemble_shaders.cmake: LANG must be glsl, hlsl or essl, not '${LANG}'")
endif()

# Text of `file` without its /* ... */ comments, blank-line runs collapsed.
function(slut_strip_block_comments text out_var)
  set(result "")
  while(TRUE)
    string(FIND "${text}" "/*" open)
    if(open EQUAL -1)
      string(APPEND result "${text}")
      break()
    endif()
    string(SUBSTRING "${text}" 0 ${open} before)
    string(APPEND result "${before}")
    math(EXPR after_open "${open} + 2")
    string(SUBSTRING "${text}" ${after_open} -1 text)
    string(FIND "${text}" "*/" close)
    if(close EQUAL -1)
      message(FATAL_ERROR "assemble_shaders.cmake: unterminated comment")
    endif()
    math(EXPR after_close "${close} + 2")
    string(SUBSTRING "${text}" ${after_close} -1 text)
  endwhile()
  string(REGEX REPLACE "[ \t]+\n" "\n" result "${result}")
  string(REGEX REPLACE "\n\n\n+" "\n\n" result "${result}")
  string(REPLACE "{\n\n" "{\n" result "${result}")
  set(${out_var} "${result}" PARENT_SCOPE)
endfunction()

# The SLUT_SHADER regions of each header, in order.
set(regions "")
string(REPLACE "|" ", kernels/" header_list "${HEADERS}")
string(REPLACE "|" ";" HEADERS "${HEADERS}")
foreach(header IN LISTS HEADERS)
  file(READ "${KERNELS_DIR}/${header}" text)
  set(found 0)
  while(TRUE)
    string(FIND "${text}" "/* SLUT_SHADER_BEGIN" begin)
    if(begin EQUAL -1)
      break()
    endif()
    string(SUBSTRING "${text}" ${begin} -1 text)
    string(FIND "${text}" "*/" begin_end)
    math(EXPR begin_end "${begin_end} + 2")
    string(SUBSTRING "${text}" ${begin_end} -1 text)
    string(FIND "${text}" "/* SLUT_SHADER_END */" end)
    if(end EQUAL -1)
      message(FATAL_ERROR "assemble_shaders.cmake: ${header}: SLUT_SHADER_BEGIN without SLUT_SHADER_END")
    endif()
    string(SUBSTRING "${text}" 0 ${end} region)
    string(SUBSTRING "${text}" ${end} -1 text)
    slut_strip_block_comments("${region}" region)
    string(STRIP "${region}" region)
    string(APPEND regions "// ---- from kernels/${header} (read the derivations there)\n${region}\n\n")
    math(EXPR found "${found} + 1")
  endwhile()
  if(found EQUAL 0)
    message(FATAL_ERROR "assemble_shaders.cmake: ${header} has no SLUT_SHADER_BEGIN region")
  endif()
endforeach()
string(STRIP "${regions}" regions)

# The Gauss-Legendre rule, from its one home (kernels/slut_airlight.h).
file(READ "${KERNELS_DIR}/slut_airlight.h" airlight_h)
set(gl16 "")
foreach(array slut_gl16_x slut_gl16_w)
  if(NOT airlight_h MATCHES "${array}\\[8\\] = {([^}]*)}")
    message(FATAL_ERROR "assemble_shaders.cmake: ${array} not found in slut_airlight.h")
  endif()
  string(REGEX REPLACE "[ \t\n]+" " " values "${CMAKE_MATCH_1}")
  string(STRIP "${values}" values)
  string(APPEND gl16 "SLUT_CONST_FLOAT8(${array}, ${values});\n")
endforeach()
string(STRIP "${gl16}" gl16)

file(READ "${SRC_DIR}/prelude.${LANG}" prelude)
file(READ "${SRC_DIR}/common.slsl" common)
string(REPLACE "@SLUT_GL16@" "${gl16}" common "${common}")
string(REPLACE "@SLUT_C_REGIONS@" "${regions}" common "${common}")
file(READ "${SRC_DIR}/${NAME}.slsl" body)
string(FIND "${body}" "@SLUT_PRELUDE@" at)
if(at EQUAL -1)
  message(FATAL_ERROR "assemble_shaders.cmake: ${NAME}.slsl has no @SLUT_PRELUDE@ line")
endif()
string(SUBSTRING "${body}" 0 ${at} doc)
math(EXPR after "${at} + 14")
string(SUBSTRING "${body}" ${after} -1 code)
string(REPLACE "@LANG@" "${lang_name}" doc "${doc}")
string(TOUPPER "SCATTERLUT_${NAME}_${LANG}" guard)

set(out "// GENERATED at build time by cmake/assemble_shaders.cmake -- do not edit. Sources:
// tables/shaders/src/${NAME}.slsl (this snippet), prelude.${LANG} (${lang_name} glue),
// common.slsl (float math), and the SLUT_SHADER regions of kernels/${header_list}
// (the axis maps and closed forms the generator and the C++ sampler compile).
//
${doc}#ifndef ${guard}
#define ${guard}

// Shared by all scatterlut snippets: included once per shader.
#ifndef SLUT_SHADER_COMMON
#define SLUT_SHADER_COMMON
${prelude}
// ==== BEGIN SHARED BODY (identical in the GLSL, GLSL ES and HLSL snippets)
${common}#endif // SLUT_SHADER_COMMON
${code}
// ==== END SHARED BODY ====
#endif // ${guard}
")
file(WRITE "${OUT}.tmp" "${out}")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.tmp")
