# CTest driver for the loader fuzzer: builds tests/fuzz/fuzz_loaders.cpp and the table
# codecs with clang -fsanitize=fuzzer,address,undefined, seeds a corpus with small valid
# binary and EXR tables made by the generator, and fuzzes for SECONDS seconds.
# -DSOURCE_DIR=… -DWORK_DIR=… -DGENERATOR=… -DSECONDS=… -DCLANGXX=…
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/corpus" "${WORK_DIR}/artifacts")
include("${SOURCE_DIR}/cmake/slut_step.cmake")
set(src "${SOURCE_DIR}/tables/src")
step(${CLANGXX} -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
     -DSCATTERLUT_HAS_OPENEXR=1 -I${SOURCE_DIR}/tables/include -I${SOURCE_DIR}/kernels
     -I/usr/include/OpenEXR -I/usr/include/Imath
     ${SOURCE_DIR}/tests/fuzz/fuzz_loaders.cpp ${src}/table.cpp ${src}/io_binary.cpp ${src}/io_exr.cpp
     -lOpenEXR-3_1 -lIex-3_1 -lIlmThread-3_1 -lImath-3_1 -lpthread -o ${WORK_DIR}/fuzz_loaders)
step(${GENERATOR} generate --out ${WORK_DIR}/tables --n-u 16 --n-w 8)
foreach(f airlight_F.slut)
  file(COPY ${WORK_DIR}/tables/${f} DESTINATION ${WORK_DIR}/corpus)
endforeach()
step(${WORK_DIR}/fuzz_loaders ${WORK_DIR}/corpus -max_total_time=${SECONDS} -max_len=65536
     -artifact_prefix=${WORK_DIR}/artifacts/ -print_final_stats=1)
message(STATUS "fuzzed the loaders for ${SECONDS} s without a finding")
