# The native SIMD width for deal.II's VectorizedArray (GRANULAR_DG_SIMD).
#
# Debian's deal.II is configured with DEAL_II_VECTORIZATION_WIDTH_IN_BITS 0:
# VectorizedArray<double> has width 1 and its matrix-free templates are
# instantiated for that width only. With GRANULAR_DG_SIMD a private copy of
# deal.II/base/config.h with the width of -march=native comes first on the
# include path of every target, and source/dg/simd_instantiations_*.cc
# instantiate MatrixFree, MappingInfo, ShapeInfo and the evaluation factories
# for VectorizedArray<double, W>. The library's width-1 code and ours never
# meet in one type (doc/performance.md, "SIMD build"; the test
# performance/simd_widths_agree compares the two builds).
set(GRANULAR_DG_SIMD_WIDTH 0)
if(GRANULAR_DG_SIMD)
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -march=native -dM -E -x c++ /dev/null
    OUTPUT_VARIABLE native_macros ERROR_QUIET)
  if(native_macros MATCHES "__AVX512F__")
    set(GRANULAR_DG_SIMD_WIDTH 512)
  elseif(native_macros MATCHES "__AVX__")
    set(GRANULAR_DG_SIMD_WIDTH 256)
  elseif(native_macros MATCHES "__SSE2__")
    set(GRANULAR_DG_SIMD_WIDTH 128)
  endif()
  find_file(DEAL_II_CONFIG_H deal.II/base/config.h HINTS ${DEAL_II_INCLUDE_DIRS} NO_CACHE)
  if(NOT DEAL_II_CONFIG_H)
    message(FATAL_ERROR "GRANULAR_DG_SIMD: deal.II/base/config.h not found")
  endif()
  file(READ ${DEAL_II_CONFIG_H} config)
  if(NOT config MATCHES "#define DEAL_II_VECTORIZATION_WIDTH_IN_BITS 0\n")
    message(FATAL_ERROR "GRANULAR_DG_SIMD expects a deal.II built with "
      "DEAL_II_VECTORIZATION_WIDTH_IN_BITS 0 (Debian's); configure with -DGRANULAR_DG_SIMD=OFF")
  endif()
  string(REPLACE "#define DEAL_II_VECTORIZATION_WIDTH_IN_BITS 0\n"
    "#define DEAL_II_VECTORIZATION_WIDTH_IN_BITS ${GRANULAR_DG_SIMD_WIDTH} // granular_dg: native width\n"
    config "${config}")
  # GCC 12 warns that the intrinsics headers' own undefined-value idiom
  # (`__m512d __Y = __Y;` in _mm512_undefined_pd) is uninitialized, in every
  # kernel they are inlined into (about 2,600 false positives a build). The
  # warnings are silenced for those headers only: they are included here,
  # first, with the two warnings off.
  string(APPEND config "
// granular_dg: the intrinsics headers without GCC's -W(maybe-)uninitialized
// false positives on their undefined-value idiom (cmake/simd.cmake)
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#  pragma GCC diagnostic push
#  pragma GCC diagnostic ignored \"-Wuninitialized\"
#  pragma GCC diagnostic ignored \"-Wmaybe-uninitialized\"
#  include <x86intrin.h>
#  pragma GCC diagnostic pop
#endif
")
  file(WRITE ${CMAKE_BINARY_DIR}/simd/deal.II/base/config.h.new "${config}")
  file(COPY_FILE ${CMAKE_BINARY_DIR}/simd/deal.II/base/config.h.new
    ${CMAKE_BINARY_DIR}/simd/deal.II/base/config.h ONLY_IF_DIFFERENT)
  target_include_directories(granular_dg_core BEFORE PUBLIC ${CMAKE_BINARY_DIR}/simd)
  message(STATUS "granular_dg: VectorizedArray<double> of ${GRANULAR_DG_SIMD_WIDTH} bits")
else()
  message(STATUS "granular_dg: VectorizedArray<double> of deal.II's width (GRANULAR_DG_SIMD=OFF)")
endif()
target_compile_definitions(granular_dg_core PUBLIC GRANULAR_DG_SIMD_WIDTH=${GRANULAR_DG_SIMD_WIDTH})
