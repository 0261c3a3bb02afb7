#include "io/checkpoint/h5_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sys/statvfs.h>

namespace grains::io::h5 {

namespace {
// HDF5 prints its error stack to stderr by default; we report errors ourselves.
void quiet_errors() {
  static const bool once = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)once;
}
}  // namespace

bool Handle::reset() {
  bool ok = true;
  if (id_ >= 0 && close_) ok = close_(id_) >= 0;
  id_ = H5I_INVALID_HID;
  return ok;
}

namespace {
// The innermost message on HDF5's error stack (e.g. the MPI error string of
// a failed MPI-IO write), or "".
std::string innermost_hdf5_error() {
  std::string out;
  auto cb = [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
    if (n == 0 && e && e->desc) *static_cast<std::string*>(data) = e->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, cb, &out);
  return out;
}
}  // namespace

void File::fail(const std::string& what, std::size_t bytes) const {
  const int e = errno;
  std::string why = e ? std::strerror(e) : innermost_hdf5_error();
  if (!e && parallel_) {
    // MPI-IO reports a failed write without the system error: when the
    // file system has less room than the write needed, that is the cause.
    const auto slash = path_.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : path_.substr(0, slash + 1);
    struct statvfs st {};
    if (::statvfs(dir.c_str(), &st) == 0) {
      const auto room = static_cast<unsigned long long>(st.f_bavail) * st.f_frsize;
      if (room < std::max<unsigned long long>(bytes, 65536))
        why = std::string(std::strerror(ENOSPC)) + ": " + std::to_string(room) + " bytes free";
    }
  }
  throw H5Error("checkpoint '" + path_ + "': " + what + (why.empty() ? std::string() : " (" + why + ")"));
}

void File::defer(const std::string& error) const {
  if (!parallel_) {
    if (!error.empty()) throw H5Error(error);
  } else if (pending_.empty()) {
    pending_ = error;
  }
}

void File::check() const { agree(""); }

void File::agree(const std::string& this_error) const {
  const std::string error = this_error.empty() ? pending_ : this_error;
  if (!parallel_) {
    if (!error.empty()) throw H5Error(error);
    return;
  }
#ifdef H5_HAVE_PARALLEL
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const int mine = error.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == size) return;
  std::vector<char> b(error.begin(), error.end());
  long long n = static_cast<long long>(b.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, first, MPI_COMM_WORLD);
  b.resize(static_cast<std::size_t>(n));
  MPI_Bcast(b.data(), static_cast<int>(n), MPI_CHAR, first, MPI_COMM_WORLD);
  throw H5Error("rank " + std::to_string(first) + ": " + std::string(b.begin(), b.end()));
#endif
}

File File::create(const std::string& path) {
  quiet_errors();
  File f;
  f.path_ = path;
  errno = 0;
  f.h_ = Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.h_.valid()) f.fail("cannot create the file");
  return f;
}

File File::create_parallel(const std::string& path) {
#ifdef H5_HAVE_PARALLEL
  quiet_errors();
  File f;
  f.path_ = path;
  f.parallel_ = true;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  f.writer_ = rank == 0;
  std::string err;
  try {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    if (!fapl.valid() || H5Pset_fapl_mpio(fapl.get(), MPI_COMM_WORLD, MPI_INFO_NULL) < 0)
      f.fail("cannot set up MPI-IO");
    // Metadata written in one collective operation at flush, not piecewise.
    H5Pset_coll_metadata_write(fapl.get(), true);
    errno = 0;
    f.h_ = Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
    if (!f.h_.valid()) f.fail("cannot create the file");
    f.dxpl_ = Handle(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
    if (!f.dxpl_.valid() || H5Pset_dxpl_mpio(f.dxpl_.get(), H5FD_MPIO_COLLECTIVE) < 0)
      f.fail("cannot set up collective transfers");
  } catch (const H5Error& e) {
    err = e.what();
  }
  // MPI_File_open is collective and fails on all ranks together (Open MPI
  // creates the file on one rank and broadcasts the outcome).
  f.agree(err);
  return f;
#else
  throw H5Error("checkpoint '" + path + "': this HDF5 has no MPI-IO (not the parallel build)");
#endif
}

File File::open_read(const std::string& path) {
  quiet_errors();
  File f;
  f.path_ = path;
  errno = 0;
  f.h_ = Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.h_.valid()) f.fail("cannot open as HDF5 (missing, truncated or not a checkpoint)");
  return f;
}

void File::close() {
  std::string err;
  try {
    errno = 0;
    // Parallel files: H5Fflush is MPI_File_sync on every rank, so each
    // rank's rows are on disk, not only rank 0's.
    if (h_.valid() && H5Fflush(h_.get(), H5F_SCOPE_GLOBAL) < 0) fail("flushing the file failed");
  } catch (const H5Error& e) {
    err = e.what();
  }
  agree(err);
  dxpl_.reset();
  try {
    errno = 0;
    if (!h_.reset()) fail("closing the file failed");
  } catch (const H5Error& e) {
    err = e.what();
  }
  agree(err);
}

void File::group(const std::string& name) const {
  std::string err;
  try {
    Handle g(H5Gcreate2(id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (!g.valid()) fail("cannot create group " + name);
  } catch (const H5Error& e) {
    err = e.what();
  }
  defer(err);
}

bool File::exists(const std::string& name) const {
  // Check each path component, as H5Lexists requires.
  std::size_t pos = 0;
  while ((pos = name.find('/', pos + 1)) != std::string::npos)
    if (H5Lexists(id(), name.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(id(), name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<std::string> File::children(const std::string& group) const {
  std::vector<std::string> out;
  auto cb = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t idx = 0;
  if (H5Literate_by_name(id(), group.c_str(), H5_INDEX_NAME, H5_ITER_INC, &idx, cb, &out, H5P_DEFAULT) < 0)
    fail("cannot list group " + group);
  return out;
}

void File::write_raw(const std::string& name, hid_t type, const void* data, std::size_t rows, std::size_t cols,
                     const std::string& unit) const {
  write_dataset(name, type, data, rows, cols, 0, rows, unit, true);
}

void File::write_rows(const std::string& name, hid_t type, const void* data, std::size_t local_rows,
                      std::size_t cols, std::size_t offset, std::size_t total_rows, const std::string& unit) const {
  write_dataset(name, type, data, local_rows, cols, offset, total_rows, unit, false);
}

void File::write_dataset(const std::string& name, hid_t type, const void* data, std::size_t local_rows,
                         std::size_t cols, std::size_t offset, std::size_t total_rows, const std::string& unit,
                         bool once) const {
  std::string err;
  try {
    const int rank = cols == 1 ? 1 : 2;
    const hsize_t dims[2] = {total_rows, cols};
    Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
    if (!space.valid()) fail("cannot create the dataspace of " + name);
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    // Parallel files allocate space at creation; every element is written
    // below, so the fill (a second pass over the file) is skipped.
    if (parallel_) H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_NEVER);
    Handle ds(H5Dcreate2(id(), name.c_str(), type, space.get(), H5P_DEFAULT, parallel_ ? dcpl.get() : H5P_DEFAULT,
                         H5P_DEFAULT),
              H5Dclose);
    if (!ds.valid()) fail("cannot create dataset " + name);
    if (total_rows * cols > 0) {
      errno = 0;
      if (!parallel_ || once) {
        // Serial files; in parallel files the items written once, by rank 0 alone (independent transfer).
        if (writer_ && H5Dwrite(ds.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
          fail("writing dataset " + name + " failed", total_rows * cols * H5Tget_size(type));
      } else {
        // Every rank takes part in the collective write, with no rows if it has none.
        const hsize_t start[2] = {offset, 0}, count[2] = {local_rows, cols};
        const hsize_t mdims[2] = {std::max<hsize_t>(local_rows, 1), cols};
        Handle mem(H5Screate_simple(rank, mdims, nullptr), H5Sclose);
        if (local_rows > 0) {
          if (H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0)
            fail("cannot select rows of " + name);
        } else {
          H5Sselect_none(space.get());
          H5Sselect_none(mem.get());
        }
        if (H5Dwrite(ds.get(), type, mem.get(), space.get(), dxpl_.get(), data) < 0)
          fail("writing dataset " + name + " failed", total_rows * cols * H5Tget_size(type));
      }
    }
  } catch (const H5Error& e) {
    err = e.what();
  }
  // Agreed on at once: a rank whose write failed must not go on alone
  // (HDF5 may take another path through the next collective call).
  agree(err);
  attribute(name, "units", unit.empty() ? "1" : unit);  // "1": dimensionless or a count
}

std::pair<std::size_t, std::size_t> File::shape(const std::string& name) const {
  if (!exists(name)) fail("has no dataset " + name);
  Handle ds(H5Dopen2(id(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail("cannot open dataset " + name);
  Handle space(H5Dget_space(ds.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0 || rank > 2) fail("dataset " + name + " has rank " + std::to_string(rank) + ", expected 1 or 2");
  hsize_t dims[2] = {0, 1};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  return {dims[0], rank == 2 ? dims[1] : 1};
}

void File::read_raw(const std::string& name, hid_t type, void* data, std::size_t rows, std::size_t cols) const {
  const auto [r, c] = shape(name);
  if (r != rows || c != cols)
    fail("dataset " + name + " is " + std::to_string(r) + " x " + std::to_string(c) + ", expected " +
         std::to_string(rows) + " x " + std::to_string(cols));
  Handle ds(H5Dopen2(id(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (rows * cols > 0 && H5Dread(ds.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail("reading dataset " + name + " failed");
}

namespace {
Handle string_type(std::size_t n) {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), n);
  H5Tset_strpad(t.get(), H5T_STR_NULLTERM);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}
}  // namespace

void File::write_string(const std::string& name, const std::string& s) const {
  std::string err;
  try {
    Handle t = string_type(s.size() + 1);
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle ds(H5Dcreate2(id(), name.c_str(), t.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail("cannot create dataset " + name);
    errno = 0;
    if (!parallel_) {
      if (H5Dwrite(ds.get(), t.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, s.c_str()) < 0) fail("writing " + name + " failed");
    } else if (writer_) {  // rank 0 writes (independent transfer), the others only create it
      if (H5Dwrite(ds.get(), t.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, s.c_str()) < 0)
        fail("writing " + name + " failed", s.size() + 1);
    }
  } catch (const H5Error& e) {
    err = e.what();
  }
  agree(err);
}

std::string File::read_string(const std::string& name) const {
  if (!exists(name)) fail("has no dataset " + name);
  Handle ds(H5Dopen2(id(), name.c_str(), H5P_DEFAULT), H5Dclose);
  Handle ft(H5Dget_type(ds.get()), H5Tclose);
  if (H5Tget_class(ft.get()) != H5T_STRING || H5Tis_variable_str(ft.get()) > 0) fail(name + " is not a fixed-length string");
  const std::size_t n = H5Tget_size(ft.get());
  std::string s(n, '\0');
  Handle t = string_type(n);
  if (H5Dread(ds.get(), t.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, s.data()) < 0) fail("reading " + name + " failed");
  s.resize(std::strlen(s.c_str()));
  return s;
}

void File::attribute(const std::string& object, const std::string& key, const std::string& value) const {
  // Parallel files: attributes are metadata, every rank passes the same value.
  std::string err;
  try {
    Handle t = string_type(value.size() + 1);
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle a(H5Acreate_by_name(id(), object.c_str(), key.c_str(), t.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT,
                               H5P_DEFAULT),
             H5Aclose);
    if (!a.valid()) fail("cannot create attribute " + key + " of " + object);
    errno = 0;
    if (H5Awrite(a.get(), t.get(), value.c_str()) < 0) fail("writing attribute " + key + " of " + object + " failed");
  } catch (const H5Error& e) {
    err = e.what();
  }
  defer(err);
}

std::string File::read_attribute(const std::string& object, const std::string& key) const {
  if (H5Aexists_by_name(id(), object.c_str(), key.c_str(), H5P_DEFAULT) <= 0)
    fail(object + " has no attribute '" + key + "'");
  Handle a(H5Aopen_by_name(id(), object.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  Handle ft(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(ft.get()) != H5T_STRING || H5Tis_variable_str(ft.get()) > 0)
    fail("attribute " + key + " of " + object + " is not a fixed-length string");
  const std::size_t n = H5Tget_size(ft.get());
  std::string s(n, '\0');
  Handle t = string_type(n);
  if (H5Aread(a.get(), t.get(), s.data()) < 0) fail("reading attribute " + key + " failed");
  s.resize(std::strlen(s.c_str()));
  return s;
}

}  // namespace grains::io::h5
