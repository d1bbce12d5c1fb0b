# `make test-sanitize` (Makefile): the suite again, against libraries and a CLI compiled
# with the sanitizers of SHAPEBENCH_SANITIZE (e.g. "address,undefined"), in the same build
# tree as `make test`. Each room's library and the CLI get a sanitized twin
# (TARGET_sanitized: the same sources at -O1 with the sanitizers, assertions on); the test
# executables get twins linked from the very same test object files
# (tests/CMakeLists.txt), so the test code is compiled once for both suites. It is not
# instrumented: it is none of the code under test, and it was half of a separate sanitizer
# build's compile (docs/testing.md#build-time).
set(SHAPEBENCH_SANITIZE "" CACHE STRING
  "build sanitized twins of the libraries, the CLI and the tests, e.g. address,undefined")

# Eigen takes malloc as 16-byte aligned except under AddressSanitizer
# (__SANITIZE_ADDRESS__), where it aligns by hand and frees accordingly. Test objects shared
# by plain and instrumented libraries must agree with both, so every file aligns by hand,
# always: a matrix allocated in one file and freed in another stays right. (It changes
# no arithmetic; the golden set checks it.)
add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=0)

set(SHAPEBENCH_SANITIZE_COMPILE_OPTIONS -O1 -g1 -UNDEBUG -fsanitize=${SHAPEBENCH_SANITIZE}
  -fno-sanitize-recover=all -fno-omit-frame-pointer -Wno-maybe-uninitialized)

# TARGET's link items with every library that has a sanitized twin replaced by the twin.
function(shapebench_twin_links out)
  set(mapped "")
  foreach(item ${ARGN})
    if(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
      set(inner ${CMAKE_MATCH_1})
      if(TARGET ${inner}_sanitized)
        set(item "$<LINK_ONLY:${inner}_sanitized>")
      endif()
    elseif(TARGET ${item}_sanitized)
      set(item ${item}_sanitized)
    endif()
    list(APPEND mapped "${item}")
  endforeach()
  set(${out} "${mapped}" PARENT_SCOPE)
endfunction()

# shapebench_sanitized_twin(TARGET): with SHAPEBENCH_SANITIZE, TARGET_sanitized, a library
# or executable of the same sources, includes, definitions, precompiled headers and unity
# batches, compiled with the sanitizers and linked against the twins of what TARGET links.
# Call it once TARGET is complete. Twins are built only on request (make test-sanitize).
function(shapebench_sanitized_twin target)
  if(NOT SHAPEBENCH_SANITIZE)
    return()
  endif()
  set(twin ${target}_sanitized)
  get_target_property(type ${target} TYPE)
  get_target_property(sources ${target} SOURCES)
  if(type STREQUAL "EXECUTABLE")
    add_executable(${twin} EXCLUDE_FROM_ALL ${sources})
    target_link_options(${twin} PRIVATE -fsanitize=${SHAPEBENCH_SANITIZE})
  else()
    add_library(${twin} STATIC EXCLUDE_FROM_ALL ${sources})
  endif()
  foreach(property INCLUDE_DIRECTORIES INTERFACE_INCLUDE_DIRECTORIES COMPILE_DEFINITIONS
                   COMPILE_OPTIONS PRECOMPILE_HEADERS UNITY_BUILD UNITY_BUILD_BATCH_SIZE)
    get_target_property(value ${target} ${property})
    if(value)
      set_property(TARGET ${twin} PROPERTY ${property} "${value}")
    endif()
  endforeach()
  target_compile_options(${twin} PRIVATE ${SHAPEBENCH_SANITIZE_COMPILE_OPTIONS})
  foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
    get_target_property(value ${target} ${property})
    if(value)
      shapebench_twin_links(mapped ${value})
      set_property(TARGET ${twin} PROPERTY ${property} "${mapped}")
    endif()
  endforeach()
  get_target_property(depends ${target} MANUALLY_ADDED_DEPENDENCIES)
  if(depends)
    add_dependencies(${twin} ${depends})
  endif()
endfunction()
