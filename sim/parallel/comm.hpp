#pragma once
// The communicator of a run: MPI_COMM_WORLD when the program was started by
// mpirun (Open MPI is the transport; nothing here is home-made), a single
// rank otherwise. Collectives used by the step loop are few and small: one
// flag reduction per step (rebuild trigger), ghost updates with the face
// neighbours, and an all-to-all of particle records at rebuilds.
#include <cstdint>
#include <string>
#include <vector>

namespace grains::sim {

class Comm {
 public:
  /// The world communicator (a one-rank stand-in without MPI).
  static Comm& world();
  /// Initialises MPI when the environment says mpirun started us (or when
  /// `force` is true); safe to call once at program start. Returns true when
  /// MPI is running.
  static bool init(int* argc, char*** argv, bool force = false);
  /// Finalises MPI if init started it.
  static void finalize();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool parallel() const { return size_ > 1; }
  bool root() const { return rank_ == 0; }

  bool any(bool local) const;
  double max(double local) const;
  double min(double local) const;
  double sum(double local) const;
  std::int64_t sum(std::int64_t local) const;
  std::int64_t max(std::int64_t local) const;
  /// Element-wise sums of a vector over all ranks (every rank gets them).
  void sum_in_place(std::vector<double>& v) const;
  void sum_in_place(std::vector<std::int64_t>& v) const;
  /// Every rank's value, in rank order.
  std::vector<std::int64_t> all_gather(std::int64_t local) const;

  /// A send to rank dest and a receive from rank src; dest/src may be this
  /// rank, or -1 for none.
  struct Transfer {
    const std::vector<char>* send;
    int dest;
    std::vector<char>* recv;  // sized by the caller (sendrecv_known)
    int src;
    int tag;
  };
  /// The transfers all posted before any is waited for (non-blocking sends
  /// and receives), so that messages to the same or different ranks overlap
  /// instead of each waiting its turn. A transfer to and from this rank is a
  /// copy.
  void sendrecv_known(std::vector<Transfer>& transfers) const;
  /// The same when the receivers do not know the sizes: all sizes travel
  /// first (tag and tag + 1 of each transfer are used), the receive buffers
  /// are sized from them (empty without a source), then all messages.
  void sendrecv(std::vector<Transfer>& transfers) const;
  /// Sends send[r] to every rank r; returns what each rank sent to us.
  std::vector<std::vector<char>> alltoallv(const std::vector<std::vector<char>>& send) const;
  /// Gathers every rank's bytes on rank 0 (others get an empty result).
  std::vector<std::vector<char>> gather(const std::vector<char>& local) const;
  /// Rank 0's bytes on every rank.
  void broadcast(std::vector<char>& bytes) const;
  void barrier() const;

  /// Agrees on an error: if any rank has a message, every rank gets the
  /// first one (lowest rank) and true; else false. Lets all ranks stop
  /// cleanly together instead of hanging in the next collective.
  bool agree_error(std::string& message) const;
  /// Last resort when a rank cannot continue and the others may be blocked.
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace grains::sim
