#include "hdf5_file_driver.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <new>

namespace tumble::io {
namespace {

/// The driver's file: HDF5's public part first, as the VFD interface requires.
struct File {
  H5FD_t pub;
  int fd = -1;
  haddr_t eoa = 0;  // end of the address space HDF5 allocated
  haddr_t eof = 0;  // end of the file as written
  dev_t device = 0;
  ino_t inode = 0;
  Hdf5DriverState* state = nullptr;  // the user's (the fapl's driver info), else own
  Hdf5DriverState own;
};

constexpr haddr_t kMaxAddress = (static_cast<haddr_t>(1) << (8 * sizeof(off_t) - 1)) - 1;

File* file_of(H5FD_t* f) { return reinterpret_cast<File*>(f); }
const File* file_of(const H5FD_t* f) { return reinterpret_cast<const File*>(f); }

/// A failure: recorded (the first one's errno is kept); whether HDF5 is told depends on the mode.
herr_t failed(File* f, int error) {
  if (f->state->error == 0) {
    f->state->error = error != 0 ? error : EIO;
    if (!f->state->closing) return -1;  // the first failure: HDF5 reports it, the writer stops
  }
  return 0;
}

extern "C" {

H5FD_t* open_file(const char* name, unsigned flags, hid_t fapl, haddr_t maxaddr) {
  if (name == nullptr || maxaddr == 0 || maxaddr > kMaxAddress) return nullptr;
  int o = (flags & H5F_ACC_RDWR) ? O_RDWR : O_RDONLY;
  if (flags & H5F_ACC_TRUNC) o |= O_TRUNC;
  if (flags & H5F_ACC_CREAT) o |= O_CREAT;
  if (flags & H5F_ACC_EXCL) o |= O_EXCL;
  const int fd = ::open(name, o | O_CLOEXEC, 0666);
  if (fd < 0) return nullptr;
  struct stat st;
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    return nullptr;
  }
  File* f = new (std::nothrow) File{};
  if (f == nullptr) {
    ::close(fd);
    return nullptr;
  }
  f->fd = fd;
  const void* info = H5Pget_driver_info(fapl);
  f->state = info != nullptr ? *static_cast<Hdf5DriverState* const*>(info) : &f->own;
  f->eof = static_cast<haddr_t>(st.st_size);
  f->device = st.st_dev;
  f->inode = st.st_ino;
  return &f->pub;
}

herr_t close_file(H5FD_t* file) {
  File* f = file_of(file);
  if (::close(f->fd) != 0 && f->state->error == 0) f->state->error = errno != 0 ? errno : EIO;
  // Never a failure here: HDF5 1.10 would keep a dangling identifier (the header says why); the
  // writer reads the error from its own state.
  delete f;
  return 0;
}

int compare(const H5FD_t* a, const H5FD_t* b) {
  const File *fa = file_of(a), *fb = file_of(b);
  if (fa->device != fb->device) return fa->device < fb->device ? -1 : 1;
  if (fa->inode != fb->inode) return fa->inode < fb->inode ? -1 : 1;
  return 0;
}

herr_t query(const H5FD_t*, unsigned long* flags) {
  if (flags != nullptr) {
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA;
  }
  return 0;
}

haddr_t get_eoa(const H5FD_t* file, H5FD_mem_t) { return file_of(file)->eoa; }

herr_t set_eoa(H5FD_t* file, H5FD_mem_t, haddr_t addr) {
  file_of(file)->eoa = addr;
  return 0;
}

haddr_t get_eof(const H5FD_t* file, H5FD_mem_t) { return file_of(file)->eof; }

herr_t get_handle(H5FD_t* file, hid_t, void** handle) {
  *handle = &file_of(file)->fd;  // as sec2: a pointer to the descriptor
  return 0;
}

herr_t read_file(H5FD_t* file, H5FD_mem_t, hid_t, haddr_t addr, size_t size, void* buffer) {
  File* f = file_of(file);
  auto* out = static_cast<unsigned char*>(buffer);
  while (size > 0) {
    const ssize_t n = ::pread(f->fd, out, size, static_cast<off_t>(addr));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return -1;
    if (n == 0) {  // past the end of the file: zeros, as sec2 gives
      std::memset(out, 0, size);
      break;
    }
    out += n;
    addr += static_cast<haddr_t>(n);
    size -= static_cast<size_t>(n);
  }
  return 0;
}

herr_t write_file(H5FD_t* file, H5FD_mem_t, hid_t, haddr_t addr, size_t size, const void* buffer) {
  File* f = file_of(file);
  if (f->state->error != 0) return 0;  // after a failure: nothing more is written (see the header)
  const auto* in = static_cast<const unsigned char*>(buffer);
  while (size > 0) {
    const ssize_t n = ::pwrite(f->fd, in, size, static_cast<off_t>(addr));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return failed(f, n < 0 ? errno : ENOSPC);
    in += n;
    addr += static_cast<haddr_t>(n);
    size -= static_cast<size_t>(n);
  }
  if (addr > f->eof) f->eof = addr;
  return 0;
}

herr_t truncate_file(H5FD_t* file, hid_t, hbool_t) {
  File* f = file_of(file);
  if (f->eoa == f->eof || f->state->error != 0) return 0;
  if (::ftruncate(f->fd, static_cast<off_t>(f->eoa)) != 0) return failed(f, errno);
  f->eof = f->eoa;
  return 0;
}

}  // extern "C"

hid_t driver_id() {
  static H5FD_class_t cls = [] {
    H5FD_class_t c{};
    c.name = "tumble_posix";
    c.maxaddr = kMaxAddress;
    c.fc_degree = H5F_CLOSE_WEAK;
    c.fapl_size = sizeof(Hdf5DriverState*);  // the driver info: where to report
    c.open = open_file;
    c.close = close_file;
    c.cmp = compare;
    c.query = query;
    c.get_eoa = get_eoa;
    c.set_eoa = set_eoa;
    c.get_eof = get_eof;
    c.get_handle = get_handle;
    c.read = read_file;
    c.write = write_file;
    c.truncate = truncate_file;
    const H5FD_mem_t map[H5FD_MEM_NTYPES] = H5FD_FLMAP_DICHOTOMY;
    for (int i = 0; i < H5FD_MEM_NTYPES; ++i) c.fl_map[i] = map[i];
    return c;
  }();
  static std::once_flag once;
  static hid_t id = H5I_INVALID_HID;
  std::call_once(once, [] { id = H5FDregister(&cls); });
  return id;
}

}  // namespace

hid_t hdf5_recording_fapl(Hdf5DriverState* state) {
  const hid_t id = driver_id();
  if (id < 0) return H5I_INVALID_HID;
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) return H5I_INVALID_HID;
  if (H5Pset_driver(fapl, id, &state) < 0) {
    H5Pclose(fapl);
    return H5I_INVALID_HID;
  }
  return fapl;
}

}  // namespace tumble::io
