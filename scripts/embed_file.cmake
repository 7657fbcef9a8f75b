# Writes OUTPUT, a C++ source defining `extern const std::string_view rast::SYMBOL` with the bytes
# of INPUT. Usage: cmake -DINPUT=... -DOUTPUT=... -DSYMBOL=... -P embed_file.cmake
file(READ "${INPUT}" hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," bytes "${hex}")
string(REGEX REPLACE "(('\\\\x..',){32})" "\\1\n" bytes "${bytes}")
file(WRITE "${OUTPUT}" "// Generated from ${INPUT}; do not edit.\n#include <string_view>\nnamespace rast {\nnamespace {\nconstexpr char kBytes[] = {\n${bytes}\n};\n}\nextern const std::string_view ${SYMBOL}(kBytes, sizeof(kBytes));\n}  // namespace rast\n")
