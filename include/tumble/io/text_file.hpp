#pragma once
// A whole text output (a rewritten robot description), written as every tumble output is: under a
// temporary name beside the final one and renamed onto it only when complete, so that a failure never
// leaves a half-written file under the final name (io/staged_file.hpp); "-" is standard output.
#include <filesystem>
#include <span>
#include <string_view>

namespace tumble {

/// Writes `text` to `path`. Throws InvalidArgument when `path` is one of `inputs` (the same file by
/// any name), or is not a file an output may replace (a directory, a block device, a socket);
/// FileError when it cannot be written. `what` names the output in messages ("the fixed model").
void write_text_file(const std::filesystem::path& path, std::string_view text,
                     std::span<const std::filesystem::path> inputs, std::string_view what);

}  // namespace tumble
