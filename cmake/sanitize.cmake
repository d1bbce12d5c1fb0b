# `make test-sanitize` (Makefile): the libraries and the CLI compiled with the sanitizers
# of SHAPEBENCH_SANITIZE (e.g. "address,undefined"), every executable linked with their
# runtimes. The test code itself is compiled without them: it is half of the sanitizer
# build's compile and none of the code under test (what the tests call in the libraries is
# instrumented; an inline function the test code also instantiates may keep the test's
# uninstrumented copy). docs/testing.md#build-time.
set(SHAPEBENCH_SANITIZE "" CACHE STRING "sanitizers for the libraries and the CLI, e.g. address,undefined")
if(SHAPEBENCH_SANITIZE)
  add_link_options(-fsanitize=${SHAPEBENCH_SANITIZE})
  # Eigen takes malloc as 16-byte aligned except under AddressSanitizer
  # (__SANITIZE_ADDRESS__), where it aligns by hand and frees accordingly: instrumented and
  # plain files must agree, or a matrix allocated in one is freed wrongly in the other.
  add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=0)
endif()

# shapebench_sanitize(TARGET): TARGET's own files compiled with the sanitizers, if any.
function(shapebench_sanitize target)
  if(SHAPEBENCH_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=${SHAPEBENCH_SANITIZE}
      -fno-sanitize-recover=all -fno-omit-frame-pointer)
  endif()
endfunction()
