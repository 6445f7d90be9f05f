# Warnings are errors in spirit: the build is kept free of them (-Wall -Wextra).
# -ffp-contract=off keeps the C++ reference from fusing a*b+c into one rounding,
# which the GLSL side controls with `precise` (see docs/architecture.md, "The shared kernel").
function(vkrt_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -ffp-contract=off)
  if(VKRT_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(VKRT_FUZZ)
    # Coverage for libFuzzer (tests/fuzz); UBSan stops at its first report, which
    # the fuzzer then counts as a crash.
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined
                           -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
