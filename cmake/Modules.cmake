# One library per module of host/ (docs/architecture.md, "Layout"), and the rules
# between them checked by the build.
#
#   vkrt_module(NAME [HEADER_ONLY] [VULKAN] [SOURCES file...] [USES module...] [LINKS target...])
#
# makes vkrt_NAME from host/NAME/'s SOURCES, linking the modules it USES publicly and
# other LINKS privately. Every build checks that host/NAME includes only its own
# headers and those of the modules it uses, directly or through another
# (cmake/check_includes.cmake), and, unless the module says VULKAN, the Vulkan headers
# are poisoned in it (cmake/no_vulkan.hpp).
function(vkrt_module name)
  cmake_parse_arguments(M "HEADER_ONLY;VULKAN" "" "SOURCES;USES;LINKS" ${ARGN})
  set(target vkrt_${name})
  set(closure ${name})
  foreach(used IN LISTS M_USES)
    get_property(used_closure GLOBAL PROPERTY vkrt_module_closure_${used})
    if(NOT used_closure)
      message(FATAL_ERROR "vkrt_module(${name}): module '${used}' is not defined (yet)")
    endif()
    list(APPEND closure ${used_closure})
  endforeach()
  list(REMOVE_DUPLICATES closure)
  set_property(GLOBAL PROPERTY vkrt_module_closure_${name} ${closure})

  if(M_HEADER_ONLY)
    add_library(${target} INTERFACE)
    set(scope INTERFACE)
  else()
    add_library(${target} STATIC ${M_SOURCES})
    set(scope PUBLIC)
    vkrt_set_warnings(${target})
    target_link_libraries(${target} PRIVATE ${M_LINKS})
  endif()
  target_include_directories(${target} ${scope} ${CMAKE_SOURCE_DIR}/host)
  foreach(used IN LISTS M_USES)
    target_link_libraries(${target} ${scope} vkrt_${used})
  endforeach()
  if(NOT M_VULKAN AND NOT M_HEADER_ONLY)
    target_compile_options(${target} PRIVATE -include ${CMAKE_SOURCE_DIR}/cmake/no_vulkan.hpp)
  endif()

  file(GLOB_RECURSE files CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/host/${name}/*.cpp
       ${CMAKE_SOURCE_DIR}/host/${name}/*.hpp)
  list(JOIN closure "," allowed)
  set(stamp ${CMAKE_BINARY_DIR}/modules/${name}.checked)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/modules)
  add_custom_command(OUTPUT ${stamp}
    COMMAND ${CMAKE_COMMAND} -DMODULE=${name} -DALLOWED=${allowed} -DDIR=${CMAKE_SOURCE_DIR}/host/${name}
            -DSTAMP=${stamp} -P ${CMAKE_SOURCE_DIR}/cmake/check_includes.cmake
    DEPENDS ${files} ${CMAKE_SOURCE_DIR}/cmake/check_includes.cmake
    COMMENT "Checking host/${name}'s includes" VERBATIM)
  add_custom_target(${target}_includes ALL DEPENDS ${stamp})
  if(NOT M_HEADER_ONLY)
    add_dependencies(${target} ${target}_includes)
  endif()
endfunction()
