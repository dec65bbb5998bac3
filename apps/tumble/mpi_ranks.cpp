#include "mpi_ranks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "tumble/error.hpp"

#ifdef TUMBLE_HAVE_MPI
#include <mpi.h>
#endif

namespace tumble::cli {

#ifdef TUMBLE_HAVE_MPI

Ranks start_ranks() {
  // OpenMPI's mpirun sets OMPI_COMM_WORLD_SIZE; Slurm's srun and MPICH's launchers PMI_SIZE/PMIX_RANK.
  if (std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr && std::getenv("PMI_SIZE") == nullptr &&
      std::getenv("PMIX_RANK") == nullptr) {
    return {};
  }
  MPI_Init(nullptr, nullptr);
  Ranks r;
  r.mpi = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &r.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &r.size);
  return r;
}

std::vector<EnsembleRow> gather_rows(const Ranks& ranks, const std::vector<EnsembleRow>& mine, size_t width) {
  if (!ranks.mpi || ranks.size == 1) {
    std::vector<EnsembleRow> all = mine;
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.run < b.run; });
    return all;
  }
  // Each row travels as width + 1 doubles, the run index first (exact: runs < 2^40).
  std::vector<double> flat;
  flat.reserve(mine.size() * (width + 1));
  for (const EnsembleRow& r : mine) {
    flat.push_back(static_cast<double>(r.run));
    flat.insert(flat.end(), r.values.begin(), r.values.end());
  }
  const int count = static_cast<int>(flat.size());
  std::vector<int> counts(static_cast<size_t>(ranks.size)), offsets(static_cast<size_t>(ranks.size));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<double> all;
  if (ranks.rank == 0) {
    int total = 0;
    for (int k = 0; k < ranks.size; ++k) {
      offsets[static_cast<size_t>(k)] = total;
      total += counts[static_cast<size_t>(k)];
    }
    all.resize(static_cast<size_t>(total));
  }
  MPI_Gatherv(flat.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
              MPI_COMM_WORLD);
  std::vector<EnsembleRow> rows;
  for (size_t at = 0; at + width + 1 <= all.size(); at += width + 1) {
    EnsembleRow r;
    r.run = static_cast<long>(all[at]);
    r.values.assign(all.begin() + static_cast<std::ptrdiff_t>(at + 1),
                    all.begin() + static_cast<std::ptrdiff_t>(at + 1 + width));
    rows.push_back(std::move(r));
  }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.run < b.run; });
  return rows;
}

void barrier(const Ranks& ranks) {
  if (ranks.mpi) MPI_Barrier(MPI_COMM_WORLD);
}

void require_same_study(const Ranks& ranks, const EnsembleStudy& study) {
  if (!ranks.mpi) return;
  const std::uint64_t mine[2] = {study.fingerprint(), study.columns().size() - 1};
  std::uint64_t root[2] = {mine[0], mine[1]};
  MPI_Bcast(root, 2, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (root[0] != mine[0] || root[1] != mine[1]) {
    throw InvalidArgument(fmt::format(
        "rank {} read another study than rank 0 (scene fingerprint {:016x} against {:016x}, {} columns "
        "against {}): every rank must read the same scene file, or one table would mix two studies; give "
        "every node the same copy (a shared file system, or the same file everywhere)",
        ranks.rank, mine[0], root[0], mine[1] + 1, root[1] + 1));
  }
}

void abort_ranks(const Ranks& ranks, int status) {
  if (ranks.mpi) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}

void finish_ranks(const Ranks& ranks) {
  if (ranks.mpi) MPI_Finalize();
}

const char* mpi_description() { return "MPI"; }

#else

Ranks start_ranks() { return {}; }
std::vector<EnsembleRow> gather_rows(const Ranks&, const std::vector<EnsembleRow>& mine, size_t) {
  std::vector<EnsembleRow> all = mine;
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.run < b.run; });
  return all;
}
void barrier(const Ranks&) {}
void require_same_study(const Ranks&, const EnsembleStudy&) {}
void abort_ranks(const Ranks&, int status) { std::exit(status); }
void finish_ranks(const Ranks&) {}
const char* mpi_description() { return "no MPI in this build"; }

#endif

}  // namespace tumble::cli
