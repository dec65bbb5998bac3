#pragma once
// Small pieces of the HDF5 C API made safe to use: identifiers closed by their owner, negative results
// turned into one FileError line, strings and numbers as attributes, fixed datasets. Shared by the
// trajectory writer and the ensemble table; private to tumble_io.
#include <hdf5.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "hdf5_file_driver.hpp"
#include "tumble/error.hpp"

namespace tumble::io {

/// An HDF5 identifier closed by the function it was opened with.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = H5I_INVALID_HID;
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  /// Closes now; false if HDF5 reported an error (e.g. flushing the file failed).
  bool reset() {
    bool ok = true;
    if (id_ >= 0 && close_) ok = close_(id_) >= 0;
    id_ = H5I_INVALID_HID;
    return ok;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

/// The reason of a failed write: the file driver's, else errno's (cleared after each success, so a
/// value left there comes from the failed call).
inline std::string reason(const io::Hdf5DriverState* driver) {
  const int error = driver != nullptr && driver->error != 0 ? driver->error : errno;
  return error != 0 ? std::strerror(error) : "HDF5 gave no reason";
}

/// Throws FileError for a negative HDF5 result.
struct Checker {
  std::string path;
  const io::Hdf5DriverState* driver = nullptr;
  hid_t operator()(hid_t id, const char* what) const {
    if (id < 0) {
      throw FileError(
          fmt::format("writing {} failed: HDF5 could not {} ({}); nothing was kept under that name", path,
                      what, reason(driver)));
    }
    errno = 0;
    return id;
  }
};

/// Object creation properties without modification times: two runs of one scene write the same bytes.
inline Handle untimed(hid_t property_class, const char* what, const Checker& check) {
  Handle props(check(H5Pcreate(property_class), what), H5Pclose);
  check(H5Pset_obj_track_times(props.get(), false), what);
  return props;
}

inline Handle string_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), H5T_VARIABLE);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);  // h5py reads UTF-8 variable-length strings as str
  return t;
}

inline void string_attribute(hid_t loc, const char* name, const std::string& value, const Checker& check) {
  const std::string what = fmt::format("write attribute {}", name);
  const Handle type = string_type();
  const Handle space(check(H5Screate(H5S_SCALAR), "create a dataspace"), H5Sclose);
  const Handle attr(check(H5Acreate2(loc, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                          what.c_str()),
                    H5Aclose);
  const char* p = value.c_str();
  check(H5Awrite(attr.get(), type.get(), &p), what.c_str());
}

template <class T>
void number_attribute(hid_t loc, const char* name, T value, hid_t type, const Checker& check) {
  const std::string what = fmt::format("write attribute {}", name);
  const Handle space(check(H5Screate(H5S_SCALAR), "create a dataspace"), H5Sclose);
  const Handle attr(check(H5Acreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), what.c_str()),
                    H5Aclose);
  check(H5Awrite(attr.get(), type, &value), what.c_str());
}

/// A fixed dataset `name` in `loc` of `shape` and native `type`, written from `data`, without times.
inline void fixed_dataset(hid_t loc, const std::string& name, hid_t type, const std::vector<hsize_t>& shape,
                          const void* data, const Checker& check) {
  const std::string what = fmt::format("write {}", name);
  const Handle space(
      check(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr), what.c_str()), H5Sclose);
  const Handle props = untimed(H5P_DATASET_CREATE, what.c_str(), check);
  const Handle set(
      check(H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT),
            what.c_str()),
      H5Dclose);
  size_t n = 1;
  for (hsize_t d : shape) n *= d;
  if (n > 0) check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), what.c_str());
}

/// A dataset of strings (variable-length UTF-8).
inline void string_dataset(hid_t loc, const std::string& name, const std::vector<std::string>& values,
                           const Checker& check) {
  const Handle type = string_type();
  std::vector<const char*> p;
  for (const std::string& v : values) p.push_back(v.c_str());
  fixed_dataset(loc, name, type.get(), {values.size()}, p.data(), check);
}

}  // namespace tumble::io
