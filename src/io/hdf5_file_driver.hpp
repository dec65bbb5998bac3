#pragma once
// An HDF5 file driver (a VFD, like HDF5's own POSIX "sec2" driver) that turns a write error into a
// recorded one instead of a crash.
//
// HDF5 1.10 cannot survive a write error while it closes a file: H5Fclose frees the file's state,
// reports the failure and leaves the identifier behind, and at exit H5_term_library closes it again,
// in freed memory (HDFGroup/hdf5 #2257, fixed in 1.14.1). On a full disk the data cached in the
// chunk cache is written by H5Dclose/H5Fclose, so that is where the error appears. This driver
// records the first failed write's errno and, from then on (and always once closing() is set),
// returns success for writes without doing them: every close then completes, nothing is left for
// the exit handler, and the writer reports the recorded error itself. Until the first failure and
// before closing() it fails writes like sec2 does, so HDF5 stops the run at the first error.
// Files are plain HDF5 files (the driver stores nothing in the superblock).
#include <hdf5.h>

namespace tumble::io {

/// What the driver tells its user about a file; owned by the user, it must outlive the file.
struct Hdf5DriverState {
  int error = 0;         ///< errno of the first failed write, truncate or close; 0 if none
  bool closing = false;  ///< set before closing: failures from now on are only recorded
};

/// A file access property list (for H5Fcreate) using the driver, reporting into `state`; negative if
/// HDF5 refused.
hid_t hdf5_recording_fapl(Hdf5DriverState* state);

}  // namespace tumble::io
