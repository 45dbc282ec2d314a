# cmake -DSPV=in.spv -DHEADER=out.h -DVAR=name -P EmbedSpirv.cmake
# Writes the SPIR-V module as `inline constexpr uint32_t VAR[] = {...};` (little-endian words).
# The header holds nothing but the words, so it is byte-identical for identical modules.
file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" n)
math(EXPR rem "${n} % 8")
if(n EQUAL 0 OR NOT rem EQUAL 0)
  message(FATAL_ERROR "${SPV}: not a SPIR-V module (${n} hex digits)")
endif()
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1," words "${hex}")
string(REGEX REPLACE "((0x........,){8})" "\\1\n    " words "${words}")
file(WRITE ${HEADER}.tmp "#pragma once\n#include <cstdint>\ninline constexpr uint32_t ${VAR}[] = {\n    ${words}\n};\n")
file(RENAME ${HEADER}.tmp ${HEADER})
