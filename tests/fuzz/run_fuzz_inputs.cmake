# CTest driver for the text-reader fuzzers: builds tests/fuzz/fuzz_inputs.cpp twice under
# clang -fsanitize=fuzzer,address,undefined — fuzz_eval (the eval line reader, with the
# runtime library and the shared math it answers with) and fuzz_scene (the scene reader,
# toml++ header-only so that it is instrumented too) — seeds each with the repository's own
# inputs (example scenes and tests/fuzz/known/scene-*, past findings; eval lines of every
# quantity) and fuzzes each for half of SECONDS.
# Limits as for the loaders (run_fuzz.cmake): 256 MiB per allocation, 1 GiB resident.
# -DSOURCE_DIR=… -DWORK_DIR=… -DSECONDS=… -DCLANGXX=…
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/obj" "${WORK_DIR}/corpus_eval" "${WORK_DIR}/corpus_scene" "${WORK_DIR}/artifacts")
include("${SOURCE_DIR}/cmake/slut_step.cmake")
# TOML_ASSERT off: toml++ asserts an internal invariant in parse_key that a byte 0x01
# after '[' breaks (tests/fuzz/known/scene-toml-assert-1); the parser then reports a syntax
# error, as the scatterlut build (NDEBUG, Debian's toml++ library) does.
set(flags -std=c++17 -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -DTOML_HEADER_ONLY=1
          "-DTOML_ASSERT(expr)=((void)0)"
          -I${SOURCE_DIR}/tables/include -I${SOURCE_DIR}/kernels -I${SOURCE_DIR}/host/src)
set(objects "")
include("${SOURCE_DIR}/tables/io_sources.cmake") # the codecs of the runtime library (built without OpenEXR here)
set(slut_io_sources ${SLUT_TABLE_IO_SOURCES} ${SLUT_TABLE_IO_NO_EXR_SOURCES})
list(TRANSFORM slut_io_sources PREPEND tables/src/)
foreach(s tables/src/table tables/src/sampler tables/src/airlight tables/src/airlight_query tables/src/airlight_avx2
          tables/src/airlight_avx512 tables/src/airlight_batch tables/src/nearlight tables/src/anisotropic
          tables/src/airlight_hg tables/src/nearlight_hg tables/src/surface tables/src/surface_table
          tables/src/airlight_rational tables/src/spot tables/src/spot_table ${slut_io_sources}
          host/src/eval host/src/json_guard host/src/scene host/src/kinds/runtime_registry
          host/src/kinds/airlight_runtime host/src/kinds/nearlight_runtime
          host/src/kinds/surface_runtime host/src/kinds/airlight_rational_runtime)
  get_filename_component(name ${s} NAME)
  step(${CLANGXX} ${flags} -fsanitize=fuzzer-no-link -c ${SOURCE_DIR}/${s}.cpp -o ${WORK_DIR}/obj/${name}.o)
  list(APPEND objects ${WORK_DIR}/obj/${name}.o)
endforeach()
step(${CLANGXX} ${flags} -fsanitize=fuzzer -DSLUT_FUZZ_EVAL ${SOURCE_DIR}/tests/fuzz/fuzz_inputs.cpp ${objects}
     -o ${WORK_DIR}/fuzz_eval)
step(${CLANGXX} ${flags} -fsanitize=fuzzer -DSLUT_FUZZ_SCENE ${SOURCE_DIR}/tests/fuzz/fuzz_inputs.cpp ${objects}
     -o ${WORK_DIR}/fuzz_scene)

file(GLOB scenes "${SOURCE_DIR}/examples/scenes/*.toml" "${SOURCE_DIR}/host/scenes/*.toml")
file(GLOB known_scenes "${SOURCE_DIR}/tests/fuzz/known/scene-*")
file(COPY ${scenes} ${known_scenes} DESTINATION ${WORK_DIR}/corpus_scene)
file(WRITE ${WORK_DIR}/corpus_eval/queries
  "{\"quantity\":\"F\",\"u\":1,\"v\":0.5}\n"
  "{\"quantity\":\"airlight\",\"sigma_s\":0.5,\"sigma_a\":0,\"intensity\":1,\"distance\":4,\"gamma\":2.84,\"length\":\"inf\"}\n"
  "{\"quantity\":\"airlight\",\"phase_g\":0.85,\"sigma_s\":[0.5,0,3],\"sigma_a\":0.1,\"intensity\":1,\"distance\":4,\"gamma\":0.3,\"length\":10}\n"
  "{\"quantity\":\"N\",\"T\":2,\"g\":0.5,\"r\":1,\"S\":\"inf\"}\n"
  "{\"quantity\":\"near_light\",\"sigma_s\":250,\"sigma_a\":2,\"intensity\":1,\"normal\":[0,0,1],\"eye_dir\":[0,0.6,0.8],\"light_pos\":[0.01,0,0.02],\"length\":0.05}\n"
  "{\"quantity\":\"surface\",\"sigma_s\":0.05,\"sigma_a\":0.01,\"intensity\":100,\"distance\":10,\"theta_s\":2.5}\n"
  "{\"quantity\":\"surface_specular\",\"sigma_s\":0.05,\"sigma_a\":0.01,\"intensity\":100,\"distance\":10,\"theta_r\":0.3,\"exponent\":20}\n"
  "\n[[[{\"a\":\"\\u00e9\"}]]]\n")

math(EXPR half "(${SECONDS} + 1) / 2")
foreach(target eval scene)
  step(${WORK_DIR}/fuzz_${target} ${WORK_DIR}/corpus_${target} -max_total_time=${half} -max_len=65536 -timeout=20
       -rss_limit_mb=1024 -malloc_limit_mb=256 -artifact_prefix=${WORK_DIR}/artifacts/${target}- -print_final_stats=1)
  message(STATUS "fuzzed the ${target} reader for ${half} s without a finding")
endforeach()
