# Assembles one GPU sampling snippet (GLSL, GLSL ES 3.00 for WebGL2, or HLSL) from its one
# source (docs/SHADERS.md, "One source"): the language-neutral body
# tables/shaders/src/<name>.slsl (texture access and the entry points), the language prelude
# (prelude.glsl / prelude.essl / prelude.hlsl: texture access, infinity, constant arrays,
# ES precision), and the shared part: the float math of common.slsl, then the kernels/
# headers the generator and the C++ runtime compile, compiled a third time as
# GLSL/HLSL in float through kernels/slut_compat.h's SLUT_SHADER branch — whole headers,
# less their `#ifndef SLUT_SHADER` blocks. Their block comments are dropped (the derivations
# stay in the headers; the snippets stay ASCII).
# Usage: cmake -DLANG=glsl|hlsl|essl|wgsl -DNAME=airlight -DSRC_DIR=tables/shaders/src
#              -DKERNELS_DIR=kernels
#              -DHEADERS="slut_compat.h|slut_axes.h|slut_airlight.h|slut_nearlight_closed.h|..."
#              -DOUT=file [-DBASE=nearlight] -P assemble_shaders.cmake
# BASE: another snippet whose code this one builds on (the anisotropic near light on the
# isotropic one): its code comes first. Every snippet's code sits in a language-neutral guard
# SLUT_<NAME>_CODE, so that a shader may include a snippet and the one built on it, in either
# order.
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
elseif(LANG STREQUAL "wgsl")
  # Not a snippet itself: the input of tables/shaders/wgsl/slut_wgsl.py, which preprocesses it
  # (with a tier's define) and translates it to WGSL. Its prelude is C-preprocessor glue.
  set(lang_name "WGSL (translator input)")
else()
  message(FATAL_ERROR "assemble_shaders.cmake: LANG must be glsl, hlsl, essl or wgsl, not '${LANG}'")
endif()
set(prelude_file "prelude.${LANG}")
if(LANG STREQUAL "wgsl")
  set(prelude_file "prelude.wgsl.h")
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

# The first block of `text` from `open` to `close` (both literal): sets block_found and, if
# found, block_before (the text before `open`), block_inside (from `open` to `close`,
# exclusive) and block_after (the text after `close`). An `open` without `close` is an error.
function(slut_take_block text open close header)
  set(block_found FALSE PARENT_SCOPE)
  string(FIND "${text}" "${open}" begin)
  if(begin EQUAL -1)
    return()
  endif()
  string(SUBSTRING "${text}" 0 ${begin} before)
  string(SUBSTRING "${text}" ${begin} -1 rest)
  string(FIND "${rest}" "${close}" end)
  if(end EQUAL -1)
    message(FATAL_ERROR "assemble_shaders.cmake: ${header}: '${open}' without '${close}'")
  endif()
  string(SUBSTRING "${rest}" 0 ${end} inside)
  string(LENGTH "${close}" close_length)
  math(EXPR after "${end} + ${close_length}")
  string(SUBSTRING "${rest}" ${after} -1 rest)
  set(block_found TRUE PARENT_SCOPE)
  set(block_before "${before}" PARENT_SCOPE)
  set(block_inside "${inside}" PARENT_SCOPE)
  set(block_after "${rest}" PARENT_SCOPE)
endfunction()

# The shared C code, header by header in order, each taken whole (its `#include "..."` lines
# dropped: the list names every header; its `#ifndef SLUT_SHADER` ... `#endif /* !SLUT_SHADER */`
# blocks dropped: C-only code the GPU preprocessor would skip anyway). A header must not keep
# the cut-out markers of the older layout (SLUT_SHADER_BEGIN/END).
set(shared "")
set(scanned "") # the shared code whose calls are checked below (all but slut_compat.h)
string(REPLACE "|" ";" HEADERS "${HEADERS}")
set(header_names "")
foreach(header IN LISTS HEADERS)
  if(header MATCHES ":")
    message(FATAL_ERROR "assemble_shaders.cmake: '${header}': headers are taken whole (no ':mode')")
  endif()
  list(APPEND header_names "kernels/${header}")
  file(READ "${KERNELS_DIR}/${header}" text)
  string(FIND "${text}" "SLUT_SHADER_BEGIN" marker)
  if(NOT marker EQUAL -1)
    message(FATAL_ERROR "assemble_shaders.cmake: ${header} has a SLUT_SHADER_BEGIN region: write the header in "
                        "the shared subset (kernels/slut_compat.h) and put C-only code in `#ifndef SLUT_SHADER` blocks")
  endif()
  while(TRUE) # (CMake regexes are greedy: one block at a time)
    slut_take_block("${text}" "\n#ifndef SLUT_SHADER" "#endif /* !SLUT_SHADER */" "${header}")
    if(NOT block_found)
      break()
    endif()
    set(text "${block_before}\n${block_after}")
  endwhile()
  slut_strip_block_comments("${text}" text)
  string(REGEX REPLACE "#include \"[^\"\n]*\"[^\n]*\n" "" text "${text}")
  string(REGEX REPLACE "\n\n\n+" "\n\n" text "${text}")
  string(STRIP "${text}" text)
  string(APPEND shared "// ---- kernels/${header} (read the derivations there)\n${text}\n\n")
  if(NOT header STREQUAL "slut_compat.h")
    string(APPEND scanned "${text}\n")
  endif()
endforeach()
string(STRIP "${shared}" shared)
string(REPLACE ";" ", " header_list "${header_names}")

# No silent fall-through to a GPU built-in: every call in the shared code must be to a
# function or macro the shared code defines, or to a math function kernels/slut_compat.h
# maps explicitly for the GPU (its SLUT_SHADER branch).
file(READ "${KERNELS_DIR}/slut_compat.h" compat_text)
string(REGEX MATCHALL "#  define [a-z0-9_]+\\(" mapped "${compat_text}")
string(REGEX MATCHALL "SLUT_FN [A-Za-z0-9_]+[ \n]+[A-Za-z0-9_]+\\(" defined_functions "${shared}")
string(REGEX MATCHALL "#define [A-Za-z0-9_]+\\(" defined_macros "${shared}")
set(known if for while switch return int float double)
foreach(item IN LISTS mapped defined_functions defined_macros)
  string(REGEX REPLACE "^.*[ \n]([A-Za-z0-9_]+)\\($" "\\1" name "${item}")
  list(APPEND known ${name})
endforeach()
string(REGEX REPLACE "#[^\n]*\n" "\n" scanned_code "${scanned}") # macro definitions: checked where used
string(REGEX MATCHALL "[A-Za-z_][A-Za-z0-9_]*[ \t]*\\(" calls "${scanned_code}")
set(unknown "")
foreach(call IN LISTS calls)
  string(REGEX REPLACE "[ \t]*\\($" "" name "${call}")
  if(NOT name MATCHES "^SLUT_" AND NOT name IN_LIST known AND NOT name IN_LIST unknown)
    list(APPEND unknown ${name})
  endif()
endforeach()
if(unknown)
  message(FATAL_ERROR "assemble_shaders.cmake: the shared code calls ${unknown}, which kernels/slut_compat.h "
                      "does not map for the GPU: add it there (and its float version to tables/shaders/src/common.slsl)")
endif()

file(READ "${SRC_DIR}/${prelude_file}" prelude)
file(READ "${SRC_DIR}/common.slsl" common)
# No switch statement in what the GPU compiles: SwiftShader (Chromium's WebGL2 without a GPU)
# took minutes of CPU to build a shader that inlines a switch several times (the warp switch,
# nine times in the near-light snippet) and seconds with the same code as a chain of ifs
# (bench/README.md, "Compile cost on SwiftShader"). Write such code as ifs.
function(slut_refuse_switch text where)
  string(REGEX MATCH "(^|[^A-Za-z0-9_])switch[ \t\n]*\\(" found "${text}")
  if(found)
    message(FATAL_ERROR "assemble_shaders.cmake: a switch statement in the code of ${NAME}.${LANG} (${where}): "
                        "write it as a chain of ifs (SwiftShader compiles an inlined switch for minutes; "
                        "bench/README.md, \"Compile cost on SwiftShader\")")
  endif()
endfunction()
slut_refuse_switch("${scanned_code}" "${header_list}")
slut_refuse_switch("${common}" "common.slsl")
string(REPLACE "@SLUT_C_HEADERS@" "${shared}" common "${common}")
# A snippet's documentation (before its @SLUT_PRELUDE@ line) and its code (after it), the
# code in the guard SLUT_<NAME>_CODE.
function(slut_read_snippet name doc_var code_var)
  file(READ "${SRC_DIR}/${name}.slsl" body)
  slut_refuse_switch("${body}" "${name}.slsl")
  string(FIND "${body}" "@SLUT_PRELUDE@" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "assemble_shaders.cmake: ${name}.slsl has no @SLUT_PRELUDE@ line")
  endif()
  string(SUBSTRING "${body}" 0 ${at} doc)
  math(EXPR after "${at} + 14")
  string(SUBSTRING "${body}" ${after} -1 code)
  string(TOUPPER "SLUT_${name}_CODE" code_guard)
  set(${doc_var} "${doc}" PARENT_SCOPE)
  set(${code_var} "#ifndef ${code_guard}\n#define ${code_guard}\n${code}#endif // ${code_guard}\n" PARENT_SCOPE)
endfunction()
slut_read_snippet(${NAME} doc code)
if(DEFINED BASE AND NOT BASE STREQUAL "")
  slut_read_snippet(${BASE} base_doc base_code)
  set(code "\n// ---- tables/shaders/src/${BASE}.slsl: the snippet this one builds on\n${base_code}${code}")
endif()
string(REPLACE "@LANG@" "${lang_name}" doc "${doc}")
string(TOUPPER "SCATTERLUT_${NAME}_${LANG}" guard)

set(out "// GENERATED at build time by cmake/assemble_shaders.cmake -- do not edit. Sources:
// tables/shaders/src/${NAME}.slsl (this snippet), ${prelude_file} (${lang_name} glue),
// common.slsl (float math), and ${header_list}
// (the code the generator and the C++ runtime compile, here in float).
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
