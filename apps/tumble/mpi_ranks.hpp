#pragma once
// MPI for `tumble ensemble` (OpenMPI from Debian; optional: built when found, TUMBLE_HAVE_MPI). Started
// only when the program was launched by mpirun/srun (their environment says so), so a plain
// `tumble ensemble` never touches MPI. Without MPI in the build, every call is the one-process answer.
#include <vector>

#include "tumble/io/ensemble.hpp"

namespace tumble::cli {

struct Ranks {
  int rank = 0;
  int size = 1;
  bool mpi = false;  ///< MPI was started (finish() must be called)
};

/// MPI_Init when launched by an MPI launcher (and this build has MPI); else the single process.
Ranks start_ranks();
/// All ranks' rows at rank 0 (sorted by run there); others get nothing back. `width` values per row.
std::vector<EnsembleRow> gather_rows(const Ranks& ranks, const std::vector<EnsembleRow>& mine, size_t width);
/// Every rank waits for the others.
void barrier(const Ranks& ranks);
/// Rank 0's study (its fingerprint and row width) sent to every rank, which throws InvalidArgument if
/// it read another: ranks that read different copies of a scene would write one table of two studies.
void require_same_study(const Ranks& ranks, const EnsembleStudy& study);
/// Ends every rank at once after an error on one of them (the others would wait forever).
[[noreturn]] void abort_ranks(const Ranks& ranks, int status);
void finish_ranks(const Ranks& ranks);
/// "MPI (OpenMPI 4.1.4)" or "no MPI in this build".
const char* mpi_description();

}  // namespace tumble::cli
