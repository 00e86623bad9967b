# CTest driver for the loader fuzzers: builds tests/fuzz/fuzz_loaders.cpp twice with the
# table codecs under clang -fsanitize=fuzzer,address,undefined — fuzz_binary (the binary
# loader) and fuzz_exr (the EXR loader) — seeds each with a small table of its format made
# by the generator (the EXR corpus also gets tests/fuzz/known/*, past findings), and fuzzes
# each for half of SECONDS. A single allocation above 256 MiB, or 1 GiB resident, is a
# finding (libFuzzer -malloc_limit_mb / -rss_limit_mb): no input of ≤ 64 KiB has a
# legitimate reason to need that.
# -DSOURCE_DIR=… -DWORK_DIR=… -DGENERATOR=… -DSECONDS=… -DCLANGXX=…
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/obj" "${WORK_DIR}/corpus_binary" "${WORK_DIR}/corpus_exr" "${WORK_DIR}/artifacts")
include("${SOURCE_DIR}/cmake/slut_step.cmake")
set(src "${SOURCE_DIR}/tables/src")
set(flags -std=c++17 -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined
          -DSCATTERLUT_HAS_OPENEXR=1 -I${SOURCE_DIR}/tables/include -I${SOURCE_DIR}/kernels
          -I/usr/include/OpenEXR -I/usr/include/Imath)
set(objects "")
include("${SOURCE_DIR}/tables/io_sources.cmake") # the codecs of the runtime library
foreach(s table ${SLUT_TABLE_IO_SOURCES} ${SLUT_TABLE_IO_EXR_SOURCES})
  step(${CLANGXX} ${flags} -fsanitize=fuzzer-no-link -c ${src}/${s}.cpp -o ${WORK_DIR}/obj/${s}.o)
  list(APPEND objects ${WORK_DIR}/obj/${s}.o)
endforeach()
set(libs -lOpenEXR-3_1 -lIex-3_1 -lIlmThread-3_1 -lImath-3_1 -lpthread)
step(${CLANGXX} ${flags} -fsanitize=fuzzer ${SOURCE_DIR}/tests/fuzz/fuzz_loaders.cpp ${objects} ${libs}
     -o ${WORK_DIR}/fuzz_binary)
step(${CLANGXX} ${flags} -fsanitize=fuzzer -DSLUT_FUZZ_EXR ${SOURCE_DIR}/tests/fuzz/fuzz_loaders.cpp ${objects} ${libs}
     -o ${WORK_DIR}/fuzz_exr)

step(${GENERATOR} generate --out ${WORK_DIR}/tables --n-u 16 --n-w 8)
file(COPY ${WORK_DIR}/tables/airlight_F.slut DESTINATION ${WORK_DIR}/corpus_binary)
file(COPY ${WORK_DIR}/tables/airlight_F.exr DESTINATION ${WORK_DIR}/corpus_exr)
file(GLOB known "${SOURCE_DIR}/tests/fuzz/known/*")
file(COPY ${known} DESTINATION ${WORK_DIR}/corpus_exr)
# Files of the version-1.1 EXR mapping (double attributes, semantic channel names), which
# the reader still reads: its older branch is fuzzed too.
file(GLOB exr_v1 "${SOURCE_DIR}/tests/data/exr-format-1.1/*.exr")
file(COPY ${exr_v1} DESTINATION ${WORK_DIR}/corpus_exr)

math(EXPR half "(${SECONDS} + 1) / 2")
foreach(format binary exr)
  step(${WORK_DIR}/fuzz_${format} ${WORK_DIR}/corpus_${format} -max_total_time=${half} -max_len=65536
       -rss_limit_mb=1024 -malloc_limit_mb=256 -artifact_prefix=${WORK_DIR}/artifacts/${format}- -print_final_stats=1)
  message(STATUS "fuzzed the ${format} loader for ${half} s without a finding")
endforeach()
