# Writes a text file into a C++ source as a NUL-terminated byte array, so the
# text ships inside the binary (HTML reports inline Chart.js this way).
#   cmake -DINPUT=file.js -DOUTPUT=file.cpp -DNAMESPACE=rigflex::io::detail -DSYMBOL=kChartJs -P embed_text.cmake
# defines  const unsigned char SYMBOL[];  (the bytes, then 0)
#          const std::size_t SYMBOL_size; (the byte count, without the 0)
# The array is written as hex bytes rather than a string literal: no limit on
# literal length, no escaping, any byte allowed.
foreach(var INPUT OUTPUT NAMESPACE SYMBOL)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "embed_text.cmake: -D${var}=... missing")
  endif()
endforeach()

file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" hex_length)
math(EXPR byte_count "${hex_length} / 2")
# 32 bytes per line: "0x2f,0x2a,..." then a newline.
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REPEAT "0x..," 32 line_pattern)
string(REGEX REPLACE "(${line_pattern})" "\\1\n" bytes "${bytes}")

get_filename_component(input_name "${INPUT}" NAME)
file(WRITE "${OUTPUT}.tmp"
  "// Generated from ${input_name} by cmake/embed_text.cmake; do not edit.\n"
  "#include <cstddef>\n\n"
  "namespace ${NAMESPACE} {\n"
  "extern const unsigned char ${SYMBOL}[];\n"
  "extern const std::size_t ${SYMBOL}_size;\n"
  "const unsigned char ${SYMBOL}[] = {\n${bytes}0};\n"
  "const std::size_t ${SYMBOL}_size = ${byte_count};\n"
  "}  // namespace ${NAMESPACE}\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
