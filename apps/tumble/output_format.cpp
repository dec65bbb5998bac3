#include "output_format.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "tumble/error.hpp"

namespace tumble::cli {

namespace {
std::string lower_extension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}
}  // namespace

bool hdf5_output(const std::filesystem::path& out, const std::string& format) {
  if (!format.empty()) return format == "hdf5";
  const std::string ext = lower_extension(out);
  return ext == ".h5" || ext == ".hdf5" || ext == ".hdf";
}

void require_known_extension(const std::filesystem::path& out, const std::string& format) {
  const std::string ext = lower_extension(out);
  if (!format.empty() || hdf5_output(out, format) || ext.empty() || ext == ".csv" || out == "-") return;
  std::error_code ec;
  const auto status = std::filesystem::status(out, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) return;  // a device
  throw InvalidArgument(fmt::format(
      "-o {}: unknown extension {}; tumble writes CSV (.csv) or HDF5 (.h5, .hdf5): name the file so, or "
      "give --format csv or --format hdf5",
      out.string(), out.extension().string()));
}

}  // namespace tumble::cli
