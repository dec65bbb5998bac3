// toml++'s implementation, compiled once for the io layer with the settings of src/io/CMakeLists.txt
// (floating-point values parsed with std::from_chars) and the guards of toml.hpp (no undefined
// behaviour on malformed text).
#define TOML_IMPLEMENTATION
#include "toml.hpp"
