# slut_tool_missing(NAMES test... LABELS label... WHY text): these tests cannot run because a
# tool they need is missing. Under SCATTERLUT_REQUIRE_ALL_TESTS (set by `make`, whose `make run`
# installs every tool) that is a configure error; otherwise each test is still registered and
# reports "skipped: <WHY>", so a missing tool shows as skipped tests, never as missing ones.
function(slut_tool_missing)
  cmake_parse_arguments(M "" "WHY" "NAMES;LABELS" ${ARGN})
  if(SCATTERLUT_REQUIRE_ALL_TESTS)
    message(FATAL_ERROR "SCATTERLUT_REQUIRE_ALL_TESTS: ${M_WHY}")
  endif()
  foreach(name IN LISTS M_NAMES)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -E echo "skipped: ${M_WHY}")
    set_tests_properties(${name} PROPERTIES LABELS "${M_LABELS}" SKIP_REGULAR_EXPRESSION "^skipped: ")
  endforeach()
endfunction()
