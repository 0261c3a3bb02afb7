#include "io/checkpoint/h5_file.hpp"

#include <cerrno>
#include <cstring>

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

void File::fail(const std::string& what) const {
  const int e = errno;
  throw H5Error("checkpoint '" + path_ + "': " + what + (e ? std::string(" (") + std::strerror(e) + ")" : ""));
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
  errno = 0;
  if (h_.valid() && H5Fflush(h_.get(), H5F_SCOPE_GLOBAL) < 0) fail("flushing the file failed");
  if (!h_.reset()) fail("closing the file failed");
}

void File::group(const std::string& name) const {
  Handle g(H5Gcreate2(id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail("cannot create group " + name);
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
  const hsize_t dims[2] = {rows, cols};
  Handle space(H5Screate_simple(cols == 1 ? 1 : 2, dims, nullptr), H5Sclose);
  if (!space.valid()) fail("cannot create the dataspace of " + name);
  Handle ds(H5Dcreate2(id(), name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail("cannot create dataset " + name);
  errno = 0;
  if (rows * cols > 0 && H5Dwrite(ds.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail("writing dataset " + name + " failed");
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
  Handle t = string_type(s.size() + 1);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle ds(H5Dcreate2(id(), name.c_str(), t.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail("cannot create dataset " + name);
  errno = 0;
  if (H5Dwrite(ds.get(), t.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, s.c_str()) < 0) fail("writing " + name + " failed");
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
  Handle t = string_type(value.size() + 1);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate_by_name(id(), object.c_str(), key.c_str(), t.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT,
                             H5P_DEFAULT),
           H5Aclose);
  if (!a.valid()) fail("cannot create attribute " + key + " of " + object);
  errno = 0;
  if (H5Awrite(a.get(), t.get(), value.c_str()) < 0) fail("writing attribute " + key + " of " + object + " failed");
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
