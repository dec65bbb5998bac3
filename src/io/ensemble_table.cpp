// An ensemble's results on disk: the table and its summary (CSV or HDF5), and the partial rows that let
// an interrupted study resume without recomputing what it finished.
#include <boost/crc.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include "hdf5_util.hpp"
#include "number_text.hpp"
#include "staged_file.hpp"
#include "tumble/error.hpp"
#include "tumble/io/ensemble.hpp"

namespace tumble {
namespace {

std::string number(double x) { return std::isfinite(x) ? std::string(io::NumberText(x)) : std::string(); }

void write_text(io::StagedFile& file, const std::string& text, const std::filesystem::path& path) {
  std::ofstream out(file.temporary(), std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) {
    file.abandon();
    throw FileError(fmt::format("writing {} failed: {}; nothing was kept under that name", path.string(),
                                std::strerror(errno)));
  }
}

void write_csv(const std::filesystem::path& path, const EnsembleStudy& study,
               const std::vector<EnsembleRow>& rows, const std::vector<ColumnSummary>& summary) {
  std::string table = fmt::format("{}\n", fmt::join(study.columns(), ","));
  for (const EnsembleRow& r : rows) {
    table += std::to_string(r.run);
    for (double v : r.values) {
      table += ',';
      table += number(v);
    }
    table += '\n';
  }
  std::string stats = "column,count";
  for (const SummaryStatistic& x : kSummaryStatistics) stats += fmt::format(",{}", x.name);
  stats += ",histogram\n";
  for (const ColumnSummary& s : summary) {
    stats += fmt::format("{},{}", s.column, s.count);
    for (const SummaryStatistic& x : kSummaryStatistics) stats += fmt::format(",{}", number(s.*x.value));
    stats += fmt::format(",{}\n", fmt::join(s.histogram, " "));
  }
  std::filesystem::path summary_path = path;
  summary_path.replace_extension(".summary.csv");
  io::StagedFile a(path), b(summary_path);
  write_text(a, table, path);
  write_text(b, stats, summary_path);
  io::commit_together(a, b);
}

void write_hdf5(const std::filesystem::path& path, const EnsembleStudy& study,
                const std::vector<EnsembleRow>& rows, const std::vector<ColumnSummary>& summary,
                const std::string& version) {
  io::StagedFile staged(path, /*direct_allowed=*/false);
  io::Hdf5DriverState driver;
  const io::Checker check{path.string(), &driver};
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  {
    const io::Handle access(check(io::hdf5_recording_fapl(&driver), "set up its file driver"), H5Pclose);
    const io::Handle file(
        check(H5Fcreate(staged.temporary().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
              "create the file"),
        H5Fclose);
    const hid_t root = file.get();
    io::string_attribute(root, "scene", study.base().text, check);
    io::string_attribute(root, "scene_file", study.base().path.string(), check);
    io::string_attribute(root, "tumble_version", version, check);
    io::number_attribute(root, "seed", static_cast<double>(study.seed()), H5T_NATIVE_DOUBLE, check);
    io::number_attribute(root, "runs", static_cast<double>(study.runs()), H5T_NATIVE_DOUBLE, check);
    const auto group = [&](const char* name) {
      const io::Handle props = io::untimed(H5P_GROUP_CREATE, "create a group", check);
      return io::Handle(
          check(H5Gcreate2(root, name, H5P_DEFAULT, props.get(), H5P_DEFAULT), "create a group"), H5Gclose);
    };
    const hsize_t R = rows.size();
    io::string_dataset(root, "columns", study.columns(), check);  // their order (a group's is alphabetical)
    {
      const io::Handle runs = group("runs");
      std::vector<double> column(R);
      for (size_t c = 0; c < study.columns().size(); ++c) {
        for (size_t r = 0; r < R; ++r)
          column[r] = c == 0 ? static_cast<double>(rows[r].run) : rows[r].values[c - 1];
        io::fixed_dataset(runs.get(), study.columns()[c], H5T_NATIVE_DOUBLE, {R}, column.data(), check);
      }
    }
    {
      const io::Handle stats = group("summary");
      std::vector<std::string> names;
      std::vector<double> count;
      std::vector<long long> histogram;
      for (const ColumnSummary& s : summary) {
        names.push_back(s.column);
        count.push_back(static_cast<double>(s.count));
        histogram.insert(histogram.end(), s.histogram.begin(), s.histogram.end());
      }
      const hsize_t C = summary.size();
      io::string_dataset(stats.get(), "column", names, check);
      io::fixed_dataset(stats.get(), "count", H5T_NATIVE_DOUBLE, {C}, count.data(), check);
      std::vector<double> values(C);
      for (const SummaryStatistic& x : kSummaryStatistics) {
        for (size_t c = 0; c < C; ++c) values[c] = summary[c].*x.value;
        io::fixed_dataset(stats.get(), x.name, H5T_NATIVE_DOUBLE, {C}, values.data(), check);
      }
      io::fixed_dataset(stats.get(), "histogram", H5T_NATIVE_LLONG, {C, 20}, histogram.data(), check);
    }
    check(H5Fflush(root, H5F_SCOPE_LOCAL), "write the file");
    driver.closing = true;
  }
  if (driver.error != 0) {
    staged.abandon();
    throw FileError(fmt::format("writing {} failed: {}; nothing was kept under that name", path.string(),
                                std::strerror(driver.error)));
  }
  staged.commit();
}

// PATH.partial-RANK: a head (magic, the study's fingerprint, the row width), then one record per
// finished run: the run's number (int64), its values (double × width) and the CRC-32 of those bytes
// (uint64). A kill can tear the last record (stdio flushes whole buffers, not records), and a power loss
// can leave zeros or stale bytes after the last good one; the checksum tells a whole record from both.
// The file is only ever appended to after its last whole record (open_partial cuts anything after it),
// so a torn record is never followed by good ones.
constexpr char kMagic[8] = {'T', 'M', 'B', 'L', 'P', 'R', 'T', '2'};
constexpr std::uintmax_t kHeadBytes = 8 + 2 * 8;

std::filesystem::path partial_name(const std::filesystem::path& path, int rank) {
  std::filesystem::path p = path;
  p += fmt::format(".partial-{}", rank);
  return p;
}

std::uint64_t record_checksum(std::int64_t run, const double* values, size_t width) {
  boost::crc_32_type crc;
  crc.process_bytes(&run, sizeof run);
  crc.process_bytes(values, sizeof(double) * width);
  return crc.checksum();
}

/// The whole records of a partial file of this study, and where the last one ends (0 if the file is
/// not this study's: another fingerprint or width, another format, or no head at all).
struct PartialScan {
  std::vector<EnsembleRow> rows;
  std::uintmax_t end = 0;
};
PartialScan scan_partial(const std::filesystem::path& file, const EnsembleStudy& study) {
  PartialScan scan;
  std::ifstream in(file, std::ios::binary);
  const std::uint64_t width = study.columns().size() - 1;
  char magic[8];
  std::uint64_t head[2];
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0 ||
      !in.read(reinterpret_cast<char*>(head), 16) || head[0] != study.fingerprint() || head[1] != width) {
    return scan;
  }
  scan.end = kHeadBytes;
  for (;;) {
    std::int64_t run = 0;
    std::uint64_t checksum = 0;
    EnsembleRow row;
    row.values.resize(width);
    if (!in.read(reinterpret_cast<char*>(&run), 8) ||
        !in.read(reinterpret_cast<char*>(row.values.data()), static_cast<std::streamsize>(8 * width)) ||
        !in.read(reinterpret_cast<char*>(&checksum), 8)) {
      break;  // the end, or a torn last record
    }
    if (checksum != record_checksum(run, row.values.data(), width) || run < 0 || run >= study.runs()) break;
    row.run = run;
    scan.rows.push_back(std::move(row));
    scan.end += 8 * (width + 2);
  }
  return scan;
}

}  // namespace

double ensemble_table_bytes(const EnsembleStudy& study) {
  // A row: its vector's values, the row itself and the allocator's header; the runs' done flags.
  const double width = static_cast<double>(study.columns().size() - 1);
  return static_cast<double>(study.runs()) *
         (8.0 * width + static_cast<double>(sizeof(EnsembleRow)) + 16.0 + 1.0);
}

void require_table_fits_in_memory(const EnsembleStudy& study) {
  const double need = ensemble_table_bytes(study);
  const double have = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                      static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (have > 0 && need > have) {
    throw InvalidArgument(fmt::format(
        "runs = {}: the table is gathered in memory to be written, about {:.3g} GB, more than this machine's "
        "{:.3g} GB; give fewer runs (several studies with different seeds cover the same ground)",
        study.runs(), need / 1e9, have / 1e9));
  }
}

void write_ensemble_table(const std::filesystem::path& path, bool hdf5, const EnsembleStudy& study,
                          const std::vector<EnsembleRow>& rows, const std::string& tumble_version) {
  const std::vector<ColumnSummary> summary = summarize(study.columns(), rows);
  if (hdf5) {
    write_hdf5(path, study, rows, summary, tumble_version);
  } else {
    write_csv(path, study, rows, summary);
  }
}

PartialRows::PartialRows(const std::filesystem::path& path, int rank, const EnsembleStudy& study)
    : name_(partial_name(path, rank)),
      width_(study.columns().size() - 1),
      last_flush_(std::chrono::steady_clock::now()) {
  const std::uint64_t head[2] = {study.fingerprint(), width_};
  // Keep the whole records of a file of this study (read_all reads them), cutting off a torn last one so
  // that new records follow whole ones; replace anything else.
  const PartialScan kept = scan_partial(name_, study);
  const bool ours = kept.end > 0;
  if (ours) {
    std::error_code ec;
    if (std::filesystem::file_size(name_, ec) != kept.end) std::filesystem::resize_file(name_, kept.end, ec);
    if (ec) {
      throw FileError(fmt::format("cannot cut the torn last row off {}: {}; remove the file and run again",
                                  name_.string(), ec.message()));
    }
  }
  if (const auto dir = name_.parent_path(); !dir.empty()) {  // -o out/study.csv: out/ may not exist yet
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
      throw FileError(fmt::format("cannot create the output directory {}: {}", dir.string(), ec.message()));
  }
  file_ = std::fopen(name_.c_str(), ours ? "ab" : "wb");
  if (file_ == nullptr)
    throw FileError(fmt::format("cannot write {}: {}", name_.string(), std::strerror(errno)));
  if (!ours && (std::fwrite(kMagic, 1, 8, file_) != 8 || std::fwrite(head, 8, 2, file_) != 2)) {
    throw FileError(fmt::format("writing {} failed: {}", name_.string(), std::strerror(errno)));
  }
}

PartialRows::~PartialRows() {
  if (file_ != nullptr) std::fclose(file_);
}

void PartialRows::add(const EnsembleRow& row) {
  const auto run = static_cast<std::int64_t>(row.run);
  const std::uint64_t checksum = record_checksum(run, row.values.data(), width_);
  if (std::fwrite(&run, 8, 1, file_) != 1 || std::fwrite(row.values.data(), 8, width_, file_) != width_ ||
      std::fwrite(&checksum, 8, 1, file_) != 1) {
    fail(errno);
  }
  if (std::chrono::steady_clock::now() - last_flush_ > std::chrono::milliseconds(500)) flush();
}

void PartialRows::flush() {
  if (std::fflush(file_) != 0) fail(errno);
  last_flush_ = std::chrono::steady_clock::now();
}

void PartialRows::fail(int error) const {
  throw FileError(fmt::format(
      "writing the finished rows to {} failed: {}; the rows written before are kept there: free some space "
      "(or raise the file size limit) and run the same command again to go on",
      name_.string(), std::strerror(error != 0 ? error : EIO)));
}

std::vector<EnsembleRow> PartialRows::read_all(const std::filesystem::path& path,
                                               const EnsembleStudy& study) {
  std::vector<EnsembleRow> rows;
  const std::filesystem::path dir = path.parent_path().empty() ? "." : path.parent_path();
  const std::string prefix = path.filename().string() + ".partial-";
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.path().filename().string().rfind(prefix, 0) != 0) continue;
    // Another study's file, or a torn head, gives no rows: those runs are computed again.
    PartialScan scan = scan_partial(entry.path(), study);
    rows.insert(rows.end(), std::make_move_iterator(scan.rows.begin()),
                std::make_move_iterator(scan.rows.end()));
  }
  return rows;
}

void PartialRows::remove_all(const std::filesystem::path& path) {
  const std::filesystem::path dir = path.parent_path().empty() ? "." : path.parent_path();
  const std::string prefix = path.filename().string() + ".partial-";
  std::error_code ec;
  std::vector<std::filesystem::path> doomed;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.path().filename().string().rfind(prefix, 0) == 0) doomed.push_back(entry.path());
  }
  for (const auto& p : doomed) std::filesystem::remove(p, ec);
}

}  // namespace tumble
