# cmake -DSCATTERLUT=… -DRENDER_FOG=… -DWORK_DIR=… [-DSCENE_FORWARD=…/fog_forward.toml] -P run_render.cmake
# Generates the default tables into WORK_DIR/tables, renders WORK_DIR/{table,exact}.png and the
# street lit by spot lights WORK_DIR/{spots_table,spots_exact}.png; with
# SCENE_FORWARD also that scene's tables into WORK_DIR/tables_forward and the anisotropic
# coloured picture from its g = 0.85 airlight table, WORK_DIR/{hg_table,hg_exact}.png; and the
# lit street (render_fog --street: ground and walls lit through the fog, Sun et al. 2005's
# surface terms from G tables that render_fog fills itself by quadrature),
# WORK_DIR/{street_table,street_exact,street_full_table}.png.
foreach(var SCATTERLUT RENDER_FOG WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_render.cmake: -D${var}=… is required")
  endif()
endforeach()
file(MAKE_DIRECTORY ${WORK_DIR}/tables)
execute_process(COMMAND ${SCATTERLUT} generate --out ${WORK_DIR}/tables
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "scatterlut generate failed (${rc}):\n${out}\n${err}")
endif()
set(hg_table "")
if(DEFINED SCENE_FORWARD)
  file(MAKE_DIRECTORY ${WORK_DIR}/tables_forward)
  execute_process(COMMAND ${SCATTERLUT} generate --scene ${SCENE_FORWARD} --out ${WORK_DIR}/tables_forward
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "scatterlut generate --scene ${SCENE_FORWARD} failed (${rc}):\n${out}\n${err}")
  endif()
  set(hg_table ${WORK_DIR}/tables_forward/airlight_Fg_g0.85.slut)
endif()
execute_process(COMMAND ${RENDER_FOG} ${WORK_DIR}/tables/airlight_F.slut
                        ${WORK_DIR}/tables/near_light_E3.slut ${WORK_DIR} ${hg_table} --street
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render_fog failed (exit ${rc})")
endif()
