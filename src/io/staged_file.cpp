#include "staged_file.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include "tumble/error.hpp"

namespace tumble::io {

StagedFile::StagedFile(std::filesystem::path final_path) : final_(std::move(final_path)) {
  temporary_ = final_;
  temporary_ += fmt::format(".tmp-{}", static_cast<long>(::getpid()));
  const std::filesystem::path dir = final_.parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec)
    throw FileError(fmt::format("cannot create the output directory {}: {}", dir.string(), ec.message()));
}

StagedFile::~StagedFile() { abandon(); }

void StagedFile::commit() {
  std::error_code ec;
  std::filesystem::rename(temporary_, final_, ec);
  if (ec) {
    abandon();
    throw FileError(
        fmt::format("cannot move {} to {}: {}", temporary_.string(), final_.string(), ec.message()));
  }
  done_ = true;
}

void StagedFile::abandon() {
  if (done_) return;
  std::error_code ec;  // best effort: there is nothing more to do if it fails
  std::filesystem::remove(temporary_, ec);
  done_ = true;
}

}  // namespace tumble::io
