# Compiles a GLSL compute shader to SPIR-V with glslangValidator and embeds the words
# as a C array (glslang's own --vn output), wrapped in an INTERFACE library whose
# include directory holds the generated header. The kernel folder is a dependency,
# so editing any shared kernel file rebuilds the shader; DEPENDS names further
# included files (the float probe's, which live outside kernel/); the list of the
# kinds' files comes from VKRT_KINDS_DIR (cmake/PrimitiveKinds.cmake); DEFINES are
# preprocessor definitions, NAME or NAME=VALUE.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(vkrt_add_shader target)
  cmake_parse_arguments(ARG "" "SOURCE;VARIABLE;INCLUDE_DIR" "DEPENDS;DEFINES" ${ARGN})
  list(TRANSFORM ARG_DEFINES PREPEND -D)
  set(out_dir ${CMAKE_BINARY_DIR}/generated)
  set(header ${out_dir}/${ARG_VARIABLE}.h)
  file(GLOB_RECURSE kernel_sources CONFIGURE_DEPENDS ${ARG_INCLUDE_DIR}/kernel/*.glsl)
  add_custom_command(
    OUTPUT ${header}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
    COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 -I${ARG_INCLUDE_DIR} -I${VKRT_KINDS_DIR} ${ARG_DEFINES}
            --vn ${ARG_VARIABLE} -o ${header} ${ARG_SOURCE}
    DEPENDS ${ARG_SOURCE} ${kernel_sources} ${VKRT_KINDS_DIR}/shape_files.glsl ${ARG_DEPENDS}
    COMMENT "Compiling ${ARG_SOURCE} to SPIR-V"
    VERBATIM)
  add_custom_target(${target}_build DEPENDS ${header})
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE ${out_dir})
  add_dependencies(${target} ${target}_build)
endfunction()
