# limn_embed_shaders(TARGET OUT_HEADER SHADERS...): compiles GLSL to SPIR-V at build time with
# glslangValidator and embeds each module as a uint32_t array in one generated header, so no shader
# path is resolved at run time. The array is named after the file: foo.comp -> foo_comp_spv.
function(limn_embed_shaders target header)
  set(outputs)
  set(includes)
  foreach(src ${ARGN})
    get_filename_component(name ${src} NAME)
    string(REPLACE "." "_" var ${name})
    set(spv_h ${CMAKE_CURRENT_BINARY_DIR}/spv/${name}.h)
    add_custom_command(OUTPUT ${spv_h}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_CURRENT_BINARY_DIR}/spv
      COMMAND Vulkan::glslangValidator --quiet -V --target-env vulkan1.2
              -I${CMAKE_CURRENT_SOURCE_DIR}/shaders --vn ${var}_spv -o ${spv_h}
              ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      IMPLICIT_DEPENDS CXX ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      COMMENT "glslang ${name}" VERBATIM)
    list(APPEND outputs ${spv_h})
    string(APPEND includes "#include \"spv/${name}.h\"\n")
  endforeach()
  file(GENERATE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${header} CONTENT "#pragma once\n#include <cstdint>\n${includes}")
  add_custom_target(${target}_spv DEPENDS ${outputs})
  add_dependencies(${target} ${target}_spv)
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_BINARY_DIR})
endfunction()
