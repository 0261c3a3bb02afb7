#pragma once
// A thin layer over the HDF5 C API for checkpoints: owning handles, and
// datasets written with their units as an attribute. Every failure throws
// H5Error naming the file and the object; HDF5's own error printing is off.
//
// A file can also be created for a parallel write (MPI-IO, when HDF5 was
// built with it): every rank of MPI_COMM_WORLD makes the same calls in the
// same order; a dataset is created with its global shape and each rank
// writes its own rows (write_rows) with collective transfers; items written
// once (write_raw, write_scalar, write_string) are written by rank 0 alone
// (independent transfer). Every data write, the flush and the close end
// with an agreement over ranks (one small reduction), so a failure on any
// rank (disk full on the rank that wrote) throws the same H5Error on all
// of them at the same operation, and they leave the file together; groups
// and attributes (metadata, written at the flush) are agreed on with the
// next data write. (Letting a rank go on after a failed collective write
// and agreeing later hung in the disk-full test: HDF5's next collective
// call is not made the same way on every rank.)
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <hdf5.h>

namespace grains::io::h5 {

struct H5Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// An owning hid_t with the matching close function.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      close_ = o.close_;
      o.id_ = H5I_INVALID_HID;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes now; returns false when the close failed (e.g. the final flush).
  bool reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

/// Element type of a per-particle array as HDF5 sees it: a native scalar and
/// the number of scalars per element (Eigen fixed-size vectors, matrices and
/// quaternions are stored as rows of their coefficients).
template <class T, class = void>
struct Elem;
template <>
struct Elem<double> { static hid_t type() { return H5T_NATIVE_DOUBLE; } static constexpr int n = 1; using S = double; };
template <>
struct Elem<std::int32_t> { static hid_t type() { return H5T_NATIVE_INT32; } static constexpr int n = 1; using S = std::int32_t; };
template <>
struct Elem<std::int64_t> { static hid_t type() { return H5T_NATIVE_INT64; } static constexpr int n = 1; using S = std::int64_t; };
template <>
struct Elem<std::uint32_t> { static hid_t type() { return H5T_NATIVE_UINT32; } static constexpr int n = 1; using S = std::uint32_t; };
template <class T>
struct Elem<T, std::enable_if_t<std::is_base_of_v<Eigen::MatrixBase<T>, T> && T::SizeAtCompileTime != Eigen::Dynamic>> {
  using S = typename T::Scalar;
  static hid_t type() { return Elem<S>::type(); }
  static constexpr int n = static_cast<int>(T::SizeAtCompileTime);
  static_assert(sizeof(T) == sizeof(S) * n, "checkpoint: Eigen type with padding");
};
template <class T, std::size_t N>
struct Elem<std::array<T, N>> {  // packed rows, e.g. a symmetric matrix's upper triangle
  using S = typename Elem<T>::S;
  static hid_t type() { return Elem<T>::type(); }
  static constexpr int n = static_cast<int>(N) * Elem<T>::n;
  static_assert(sizeof(std::array<T, N>) == sizeof(T) * N, "checkpoint: array with padding");
};
template <class Q>
struct Elem<Eigen::Quaternion<Q>> {  // coefficient order x, y, z, w
  using S = Q;
  static hid_t type() { return Elem<Q>::type(); }
  static constexpr int n = 4;
  static_assert(sizeof(Eigen::Quaternion<Q>) == sizeof(Q) * 4, "checkpoint: quaternion with padding");
};

class File {
 public:
  static File create(const std::string& path);  // truncates
  /// Collective over MPI_COMM_WORLD: creates (truncates) the file through
  /// MPI-IO. Throws on every rank when it fails on any.
  static File create_parallel(const std::string& path);
  /// True when HDF5 has MPI-IO (the Debian Open MPI build).
  static constexpr bool can_write_parallel() {
#ifdef H5_HAVE_PARALLEL
    return true;
#else
    return false;
#endif
  }
  bool parallel() const { return parallel_; }
  static File open_read(const std::string& path);
  const std::string& path() const { return path_; }
  hid_t id() const { return h_.get(); }
  /// Flushes and closes; throws when HDF5 could not complete the file.
  void close();
  /// Parallel files: every rank calls it; throws the same H5Error on all
  /// ranks when an operation since the last check failed on any. Serial
  /// files throw at the failing operation itself.
  void check() const;

  void group(const std::string& name) const;
  bool exists(const std::string& name) const;
  /// Names of the links directly under a group.
  std::vector<std::string> children(const std::string& group) const;

  /// rows x cols array of a native scalar type (cols == 1: a 1-D dataset).
  void write_raw(const std::string& name, hid_t type, const void* data, std::size_t rows, std::size_t cols,
                 const std::string& unit) const;
  /// A dataset of total_rows x cols of which this rank writes local_rows
  /// rows starting at row `offset` (parallel files; collective). In a serial
  /// file local_rows == total_rows and offset == 0.
  void write_rows(const std::string& name, hid_t type, const void* data, std::size_t local_rows, std::size_t cols,
                  std::size_t offset, std::size_t total_rows, const std::string& unit) const;
  template <class T>
  void write_vector_rows(const std::string& name, const std::vector<T>& v, int width, std::size_t offset,
                         std::size_t total_rows, const std::string& unit) const {
    const std::size_t cols = static_cast<std::size_t>(Elem<T>::n) * static_cast<std::size_t>(width);
    write_rows(name, Elem<T>::type(), v.data(), width > 0 ? v.size() / static_cast<std::size_t>(width) : 0, cols,
               offset, total_rows, unit);
  }
  /// Reads a dataset that must have exactly rows x cols elements of `type`.
  void read_raw(const std::string& name, hid_t type, void* data, std::size_t rows, std::size_t cols) const;
  /// Shape of a dataset: {rows, cols}; cols is 1 for 1-D datasets.
  std::pair<std::size_t, std::size_t> shape(const std::string& name) const;

  template <class T>
  void write_vector(const std::string& name, const std::vector<T>& v, int width, const std::string& unit) const {
    const std::size_t cols = static_cast<std::size_t>(Elem<T>::n) * static_cast<std::size_t>(width);
    write_raw(name, Elem<T>::type(), v.data(), width > 0 ? v.size() / static_cast<std::size_t>(width) : 0, cols, unit);
  }
  /// Reads into v, resized to rows * width elements.
  template <class T>
  void read_vector(const std::string& name, std::vector<T>& v, std::size_t rows, int width) const {
    v.resize(rows * static_cast<std::size_t>(width));
    read_raw(name, Elem<T>::type(), v.data(), rows, static_cast<std::size_t>(Elem<T>::n) * static_cast<std::size_t>(width));
  }
  template <class T>
  void write_scalar(const std::string& name, const T& x, const std::string& unit) const {
    write_raw(name, Elem<T>::type(), &x, 1, 1, unit);
  }
  template <class T>
  T read_scalar(const std::string& name) const {
    T x{};
    read_raw(name, Elem<T>::type(), &x, 1, 1);
    return x;
  }
  void write_string(const std::string& name, const std::string& s) const;
  std::string read_string(const std::string& name) const;
  /// String attribute on an object ("/" for the file).
  void attribute(const std::string& object, const std::string& key, const std::string& value) const;
  std::string read_attribute(const std::string& object, const std::string& key) const;

 private:
  /// Throws H5Error for `what`, with the system error, or HDF5's, and for
  /// parallel files a full disk when the folder has less than `bytes` (at
  /// least 64 KiB) free.
  [[noreturn]] void fail(const std::string& what, std::size_t bytes = 0) const;
  /// Parallel files: every rank passes its error (empty: none); when any
  /// rank has one, all throw H5Error with the lowest rank's. Serial: throws
  /// a non-empty error.
  void agree(const std::string& error) const;
  /// Serial: throws a non-empty error; parallel: keeps the first for agree().
  void defer(const std::string& error) const;
  void write_dataset(const std::string& name, hid_t type, const void* data, std::size_t local_rows, std::size_t cols,
                     std::size_t offset, std::size_t total_rows, const std::string& unit, bool once) const;
  mutable std::string pending_;  // this rank's first error since the last agreement (parallel files)
  std::string path_;
  Handle h_;
  Handle dxpl_;  // collective transfers (parallel files)
  bool parallel_ = false, writer_ = true;  // writer_: writes the once-only items (rank 0)
};

}  // namespace grains::io::h5
