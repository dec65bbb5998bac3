#pragma once
// One function per reader (toml++ and toml11 share the namespace `toml`: each lives in its own file).
#include <string>

/// Parses `text` into the reader's tree and frees it; throws the reader's error for a bad file.
void parse_tomlpp(const std::string& text, const std::string& name);
void parse_toml11(const std::string& text, const std::string& name);
void parse_cpptoml(const std::string& text, const std::string& name);
