# The table file codecs of the runtime library (tables/src, names without .cpp): one list for
# tables/CMakeLists.txt and the fuzzers (tests/fuzz/run_fuzz*.cmake), which compile them on
# their own under the sanitizers.
set(SLUT_TABLE_IO_SOURCES
  io_storage         # binary16/binary32 rounding, storage error, payload bytes
  io_checksum        # FNV-1a-64
  io_binary_encode   # binary encoder, format limits
  io_binary_decode   # binary decoder (distrusts its input)
  io_files           # bounded reads, atomic writes, the signal-safe temporary-file registry
  io_dispatch        # load_table: the format by its magic number
  io_metadata        # metadata numbers as decimal text
  io_ktx2)           # KTX 2.0 encoder
set(SLUT_TABLE_IO_EXR_SOURCES   # with OpenEXR
  io_exr_encode      # EXR encoder
  io_exr_decode      # EXR decoder (distrusts its input)
  io_exr_prescan)    # the raw header walk before OpenEXR reads it
set(SLUT_TABLE_IO_NO_EXR_SOURCES io_exr_unavailable) # without: the EXR entry points say so
