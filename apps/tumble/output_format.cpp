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

bool aem_output(const std::filesystem::path& out, const std::string& format) {
  if (!format.empty()) return format == "aem";
  return lower_extension(out) == ".aem";
}

void require_known_extension(const std::filesystem::path& out, const std::string& format, bool aem_allowed) {
  const std::string ext = lower_extension(out);
  if (!aem_allowed && format.empty() && aem_output(out, format)) {
    throw InvalidArgument(
        fmt::format("-o {}: a study writes tables, CSV (.csv) or HDF5 (.h5, .hdf5); an attitude message "
                    "(.aem) is written "
                    "by tumble run, for one run",
                    out.string()));
  }
  if (!format.empty() || hdf5_output(out, format) || (aem_allowed && aem_output(out, format)) ||
      ext.empty() || ext == ".csv" || out == "-")
    return;
  std::error_code ec;
  const auto status = std::filesystem::status(out, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) return;  // a device
  throw InvalidArgument(fmt::format(
      "-o {}: unknown extension {}; tumble writes CSV (.csv){}: name the file so, "
      "or give --format csv{}",
      out.string(), out.extension().string(),
      aem_allowed ? ", HDF5 (.h5, .hdf5) or CCSDS attitude messages (.aem)" : " or HDF5 (.h5, .hdf5)",
      aem_allowed ? ", hdf5 or aem" : " or --format hdf5"));
}

}  // namespace tumble::cli
