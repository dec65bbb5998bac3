#pragma once
// Trajectory outputs. A writer receives every output sample of a run and writes, for each body and
// particle, the chosen output fields (by default the pose and velocity of each body's reference frame,
// world), and the sample's invariants and drifts. Both lists come from sim/output_fields.hpp, which
// names, documents and computes every column and dataset.
//
// Files are written under a temporary name next to the final one (NAME.tmp-PID) and renamed only by
// commit(), so a final name never holds a half-written file:
//  - commit() after a complete run, or after the user interrupted it (Ctrl-C): the samples written
//    so far form a valid file (HDF5: attribute complete = 0 and the time reached); a CSV trajectory
//    and its diagnostics are moved into place together (both or neither; SIGINT, SIGTERM and SIGHUP
//    are held back in the calling thread meanwhile);
//  - destroyed without commit() (an error, e.g. the state became non-finite, or a write failed): the
//    temporary files are deleted and nothing appears under the final names.
// A symlink as output is followed (its target is replaced, the link stays); a character device
// (/dev/null) or a FIFO is written straight through, never replaced; "-" is standard output (CSV);
// a directory, a block device or a socket is refused, and so are devices, FIFOs and "-" for HDF5. A
// new writer removes the temporaries that killed runs left beside its files (NAME.tmp-PID of a PID
// that is no longer alive). A write error (a full disk) throws FileError at once.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/forces/model.hpp"
#include "tumble/io/geometry.hpp"
#include "tumble/sim/drift_monitor.hpp"
#include "tumble/sim/output_fields.hpp"
#include "tumble/sim/sensitivities.hpp"

namespace tumble {

/// What is stored with a trajectory besides the samples.
struct TrajectoryInfo {
  std::string scene_text;           ///< the scene file's contents
  std::string scene_path;           ///< as given on the command line
  std::string tumble_version;       ///< e.g. "0.1.0"
  RunSettings settings;             ///< as run (after command-line overrides)
  std::vector<std::string> fields;  ///< per-body output fields (output_fields.hpp); empty: the defaults
  bool events = false;  ///< the run watches events: the writer stores every crossing given to event()
  /// The bodies' surfaces, mass properties and the springs, stored for `tumble report` (HDF5: group
  /// `geometry`; CSV: OUT.run.json with the run's facts); none when null.
  std::shared_ptr<const SceneGeometry> geometry;
  /// Euler-angle fields made continuous from sample to sample (AngleUnwrapper; --unwrap-angles).
  bool unwrap_angles = false;
};

class TrajectoryWriter {
 public:
  virtual ~TrajectoryWriter() = default;
  /// One output sample (bodies first, then particles, in model order).
  virtual void write(const Model& model, const SystemState& state, const DriftSample& drift) = 0;
  /// An event crossing: its name, the row (body or particle) it watches and its time. Stored only
  /// when TrajectoryInfo::events: CSV in OUT.events.csv beside a regular trajectory file (t,event,body,
  /// one row per crossing in time order), HDF5 in the group `events` (datasets t, event, body).
  virtual void event(std::string_view name, size_t row, double t) = 0;
  /// What the run found, stored with it when the writer keeps facts (geometry set): its warnings (e.g.
  /// the drift monitor's). The wall-clock time is not stored (outputs are byte-identical run to run).
  /// Call before commit().
  virtual void outcome(double wall_time_s, const std::vector<std::string>& warnings) = 0;
  /// Finishes the files and moves them to their final names. `complete` is false when the run was
  /// interrupted before its end. Throws FileError if writing failed (the temporaries are removed).
  virtual void commit(bool complete) = 0;
  /// The final paths of the files this writer produces.
  virtual std::vector<std::filesystem::path> outputs() const = 0;
  /// Samples written so far.
  virtual long samples() const = 0;
  /// The sensitivities of the sample just written (sim/sensitivities.hpp). HDF5 stores them in the
  /// datasets `stm` and `parameter_sensitivity`; a CSV writer throws InvalidArgument (tumble run refuses
  /// --sensitivities with CSV before it starts).
  virtual void sensitivities(const Sensitivities& /*s*/);
  /// Makes what was written so far durable in the (temporary) files: flushed and fsync'ed (a checkpoint
  /// is about to name them). Throws FileError.
  virtual void sync() {}
};

/// CSV files that an earlier part of the same run wrote, to be continued (`tumble resume`): the files
/// now under the final names are copied into the new temporaries up to the end of sample `samples`,
/// and writing continues from there. Checked: the header is this run's, the files hold that many
/// samples, and the last one kept is at `last_t`.
struct CsvContinuation {
  long samples = 0;
  double last_t = 0.0;
};

/// CSV: `trajectory` ("-": standard output) has the header t,body, then the columns of each field (by default
/// px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz) and one row per body and per particle per sample, 17
/// significant digits; `diagnostics` has t and the columns of every SystemField, one row per sample
/// (an empty path: no diagnostics file). Throws InvalidArgument if both name the same file. The writer
/// keeps `info` for OUT.run.json (moved in, it is not copied: a scene's text can be 50 MB).
std::unique_ptr<TrajectoryWriter> make_csv_writer(const std::filesystem::path& trajectory,
                                                  const std::filesystem::path& diagnostics,
                                                  const Model& model, TrajectoryInfo info,
                                                  const std::optional<CsvContinuation>& continuation = {});

/// HDF5 (one file): datasets t, names, one (n, N, width) dataset per field, and the group diagnostics;
/// the scene text, tumble version and run settings as attributes (hdf5_writer.cpp).
std::unique_ptr<TrajectoryWriter> make_hdf5_writer(const std::filesystem::path& path, const Model& model,
                                                   const TrajectoryInfo& info);

/// What a CCSDS attitude message names besides the samples.
struct AemHeader {
  std::string epoch = "2000-01-01T12:00:00.000";  ///< the UTC date of t = 0 (default: J2000's)
  std::string ref_frame = "EME2000";  ///< REF_FRAME_A: the inertial frame tumble's world axes stand for
};

/// A CCSDS Attitude Ephemeris Message, KVN, version 2.0 (CCSDS 504.0-B-2; docs/scene-format.md): one
/// segment per body (OBJECT_NAME and OBJECT_ID its name) of ATTITUDE_TYPE QUATERNION/ANGVEL, a line
/// per sample: the date (epoch + t, UTC), the quaternion of the body's reference frame (REF_FRAME_B =
/// SC_BODY_1) relative to REF_FRAME_A, scalar last, and the angular velocity in the reference frame's
/// axes in deg/s. Particles have no attitude and are left out; events and diagnostics are not stored.
/// The file is written whole at commit (each segment's START and STOP times come first). Throws
/// InvalidArgument for an invalid epoch or frame name, or a model without bodies.
std::unique_ptr<TrajectoryWriter> make_aem_writer(const std::filesystem::path& path, const Model& model,
                                                  const TrajectoryInfo& info, const AemHeader& header);

/// `inner`, its samples formatted and written on a thread of its own while the run steps on
/// (background_writer.cpp): the same files, byte for byte. write() copies the sample and returns once
/// the previous one is written; every other call waits for that too, and a write error is thrown by the
/// next call. Pays where a sample takes long to write (a CSV sample of thousands of bodies); the inner
/// writer must not share a library with the calling thread that is not thread-safe (HDF5 is not).
/// Where no thread can be started (a limit on threads or memory), `inner` itself is returned.
std::unique_ptr<TrajectoryWriter> write_in_background(std::unique_ptr<TrajectoryWriter> inner);

/// True if the two paths name the same file: the same device and inode when both exist (so hard
/// links, symlinks and "./x/../f" spellings count), else the same path once "." and ".." and symlinked
/// directories are resolved. "-" (standard output) is only the same as "-".
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// The default diagnostics path for a CSV trajectory: out/x.csv → out/x.diagnostics.csv.
std::filesystem::path diagnostics_path(const std::filesystem::path& trajectory);
/// OUT.events.csv for OUT.csv: where a CSV run's event crossings go.
std::filesystem::path events_path(const std::filesystem::path& trajectory);

}  // namespace tumble
