# cmake -DSPV=in.spv -DHEADER=out.h -DVAR=name -P EmbedSpirv.cmake
# Writes the SPIR-V module as `inline constexpr uint32_t VAR[] = {...};` (little-endian words).
# The header holds nothing but the words, and is only rewritten when they change, so editing a
# comment in an included .glsl file does not recompile the C++ that embeds the module.
file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" n)
math(EXPR rem "${n} % 8")
if(n EQUAL 0 OR NOT rem EQUAL 0)
  message(FATAL_ERROR "${SPV}: not a SPIR-V module (${n} hex digits)")
endif()
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1," words "${hex}")
string(REGEX REPLACE "((0x........,){8})" "\\1\n    " words "${words}")
file(WRITE ${HEADER}.tmp "#pragma once\n#include <cstdint>\ninline constexpr uint32_t ${VAR}[] = {\n    ${words}\n};\n")
file(COPY_FILE ${HEADER}.tmp ${HEADER} ONLY_IF_DIFFERENT)
file(REMOVE ${HEADER}.tmp)
