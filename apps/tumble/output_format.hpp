#pragma once
// Which format an output file is written in, from --format or the file's name: one rule for `tumble run`
// and `tumble ensemble`.
#include <filesystem>
#include <string>

namespace tumble::cli {

/// True for HDF5, false for CSV. `format` is --format ("csv", "hdf5" or empty). Without it the
/// extension decides, in any case: .h5, .hdf5, .hdf are HDF5; anything else CSV (and
/// require_known_extension refuses what is neither).
bool hdf5_output(const std::filesystem::path& out, const std::string& format);

/// True for a CCSDS attitude message: --format aem, or without --format the extension .aem (any case).
bool aem_output(const std::filesystem::path& out, const std::string& format);

/// Without --format, refuses (InvalidArgument) an output whose extension is neither CSV's (.csv, or
/// none) nor HDF5's: a silent CSV in out.xyz is a file the user's tools then misread. Standard output
/// (-) and a device or FIFO are CSV whatever their names. Called after the checks that an output is not
/// an input, which say more. `aem_allowed`: the command writes attitude messages (tumble run; a study
/// refuses .aem).
void require_known_extension(const std::filesystem::path& out, const std::string& format, bool aem_allowed);

}  // namespace tumble::cli
