#include "tumble/io/text_file.hpp"

#include <cstdio>
#include <fstream>

#include <fmt/format.h>

#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/io/trajectory_writer.hpp"

namespace tumble {

void write_text_file(const std::filesystem::path& path, std::string_view text,
                     std::span<const std::filesystem::path> inputs, std::string_view what) {
  for (const std::filesystem::path& input : inputs) {
    if (same_file(path, input)) {
      throw InvalidArgument(
          fmt::format("{} {} is the input {}: tumble never overwrites an input; give another "
                      "output file",
                      what, path.string(), input.string()));
    }
  }
  io::StagedFile file(path);
  if (file.kind() == io::OutputKind::standard_output) {
    if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
      throw FileError(fmt::format("{}: cannot write to standard output", what));
    return;
  }
  {
    std::ofstream out(file.temporary(), std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) throw FileError(fmt::format("{} {}: cannot write it (disk full?)", what, path.string()));
  }
  file.commit();
}

}  // namespace tumble
