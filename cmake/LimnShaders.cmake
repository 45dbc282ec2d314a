# limn_embed_shaders(TARGET OUT_HEADER SHADERS... [INCLUDE_DIRS dirs...]): compiles GLSL to SPIR-V
# at build time with glslangValidator and embeds each module as a uint32_t array in one generated
# header, so no shader path is resolved at run time. The array is named after the file:
# foo.comp -> foo_comp_spv. Shaders may #include files from their own folder, from lib/gpu/shaders
# (limn's shared GLSL helpers) and from INCLUDE_DIRS.
#
# Every .glsl file in those folders is a dependency of every shader: IMPLICIT_DEPENDS is ignored by
# Ninja, and a changed include must never leave a stale embedded module behind. (glslang's own
# --depfile is used as well, so an include from anywhere is tracked exactly.)
#
# Each target also gets a CTest test, spirv_check_<target>, that runs spirv-val on its modules and
# refuses what WebGPU cannot express (cmake/CheckSpirv.cmake).
set(LIMN_SHADER_COMMON_DIR ${CMAKE_CURRENT_LIST_DIR}/../lib/gpu/shaders)
find_program(LIMN_SPIRV_VAL spirv-val)
find_program(LIMN_SPIRV_DIS spirv-dis)

function(limn_embed_shaders target header)
  cmake_parse_arguments(ARG "" "" "INCLUDE_DIRS" ${ARGN})
  get_filename_component(common_dir ${LIMN_SHADER_COMMON_DIR} ABSOLUTE)
  set(include_dirs ${CMAKE_CURRENT_SOURCE_DIR}/shaders ${common_dir} ${ARG_INCLUDE_DIRS})
  list(REMOVE_DUPLICATES include_dirs)
  set(include_flags)
  set(glsl_includes)
  foreach(dir ${include_dirs})
    list(APPEND include_flags -I${dir})
    file(GLOB found CONFIGURE_DEPENDS ${dir}/*.glsl)
    list(APPEND glsl_includes ${found})
  endforeach()

  set(outputs)
  set(modules)
  set(includes)
  foreach(src ${ARG_UNPARSED_ARGUMENTS})
    get_filename_component(name ${src} NAME)
    string(REPLACE "." "_" var ${name})
    set(spv ${CMAKE_CURRENT_BINARY_DIR}/spv/${name}.spv)
    set(spv_h ${CMAKE_CURRENT_BINARY_DIR}/spv/${name}.h)
    add_custom_command(OUTPUT ${spv}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_CURRENT_BINARY_DIR}/spv
      COMMAND Vulkan::glslangValidator --quiet -V --target-env vulkan1.2 ${include_flags}
              --depfile ${spv}.d -o ${spv} ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${src} ${glsl_includes}
      DEPFILE ${spv}.d
      COMMENT "glslang ${name}" VERBATIM)
    add_custom_command(OUTPUT ${spv_h}
      COMMAND ${CMAKE_COMMAND} -DSPV=${spv} -DHEADER=${spv_h} -DVAR=${var}_spv
              -P ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      DEPENDS ${spv} ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      COMMENT "embed ${name}" VERBATIM)
    list(APPEND outputs ${spv_h})
    list(APPEND modules ${spv})
    string(APPEND includes "#include \"spv/${name}.h\"\n")
  endforeach()
  file(GENERATE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${header} CONTENT "#pragma once\n#include <cstdint>\n${includes}")
  add_custom_target(${target}_spv DEPENDS ${outputs})
  add_dependencies(${target} ${target}_spv)
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_BINARY_DIR})
  if(LIMN_SPIRV_VAL AND LIMN_SPIRV_DIS)
    add_test(NAME spirv_check_${target}
      COMMAND ${CMAKE_COMMAND} -DSPIRV_VAL=${LIMN_SPIRV_VAL} -DSPIRV_DIS=${LIMN_SPIRV_DIS}
              "-DMODULES=${modules}" -P ${PROJECT_SOURCE_DIR}/cmake/CheckSpirv.cmake)
  endif()
endfunction()
