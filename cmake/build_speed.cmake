# Build time (docs/testing.md#build-time). Most of a library file's compile was parsing the
# same heavy headers again (CLI11 2.8 s, nlohmann-json 1.5 s, Eigen/Dense 1.1 s, yaml-cpp
# 0.8 s at -O0) and instantiating the same templates again. Each library precompiles the
# heavy headers its files use, once, and compiles its files in unity batches: a batch is
# one translation unit, so what the files share is parsed and instantiated once.
#
# Neither changes a result: the same code is compiled with the same flags (no -ffast-math,
# no FMA contraction in ISO C++ mode), and the golden set checks it bit for bit. What it
# asks of a source file: the names in its anonymous namespace must not collide with a
# neighbour's in the same batch (give them names of their own, or share one definition from
# a header).
#
#   -DSHAPEBENCH_PCH=OFF         no precompiled headers (to check that every file includes
#                                what it uses)
#   -DSHAPEBENCH_UNITY_BATCH=0   one file a translation unit (quicker rebuilds after an edit)
option(SHAPEBENCH_PCH "precompile each library's heavy headers" ON)
set(SHAPEBENCH_UNITY_BATCH 16 CACHE STRING "library files per unity batch (0: no unity build)")

set(SHAPEBENCH_STD_HEADERS <algorithm> <cmath> <cstddef> <cstdio> <cstdlib> <fstream>
  <functional> <limits> <map> <memory> <optional> <set> <sstream> <stdexcept> <string>
  <utility> <variant> <vector>)

# shapebench_build_fast(TARGET HEADER...): TARGET's files compiled in unity batches, with
# HEADER... and the standard headers above precompiled.
function(shapebench_build_fast target)
  if(SHAPEBENCH_PCH)
    target_precompile_headers(${target} PRIVATE ${ARGN} ${SHAPEBENCH_STD_HEADERS})
  endif()
  if(SHAPEBENCH_UNITY_BATCH GREATER 0)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON
      UNITY_BUILD_BATCH_SIZE ${SHAPEBENCH_UNITY_BATCH})
  endif()
endfunction()
