# SFFCAL_LARGER_INLINING_LIMITS: GCC's inlining growth limits raised, for the few files whose hot
# function is one large body of many small fixed-size Eigen (or Jet) expressions. At the default
# limits GCC stops inlining them and calls each 6-vector kernel out of line; the arithmetic, and so
# every result, is the same either way (bench/RESULTS.md, "Fourth step"). Set on source files with
# set_source_files_properties(... COMPILE_OPTIONS "${SFFCAL_LARGER_INLINING_LIMITS}").
set(SFFCAL_LARGER_INLINING_LIMITS)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(SFFCAL_LARGER_INLINING_LIMITS "--param=large-function-growth=400;--param=inline-unit-growth=400")
endif()
