// toml++'s implementation, compiled once for the io layer with the settings of src/io/CMakeLists.txt
// (floating-point values parsed with std::from_chars).
#define TOML_IMPLEMENTATION
#include <toml++/toml.h>
