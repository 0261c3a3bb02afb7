#include "sim/parallel/comm.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#ifdef GRAINS_HAVE_MPI
#include <mpi.h>
#endif

namespace grains::sim {

namespace {
bool g_started = false;

[[maybe_unused]] bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}
}  // namespace

Comm& Comm::world() {
  static Comm c;
#ifdef GRAINS_HAVE_MPI
  static bool set = false;
  if (!set) {
    int on = 0;
    MPI_Initialized(&on);
    if (on) {
      MPI_Comm_rank(MPI_COMM_WORLD, &c.rank_);
      MPI_Comm_size(MPI_COMM_WORLD, &c.size_);
      set = true;
    }
  }
#endif
  return c;
}

bool Comm::init([[maybe_unused]] int* argc, [[maybe_unused]] char*** argv, [[maybe_unused]] bool force) {
#ifdef GRAINS_HAVE_MPI
  int on = 0;
  MPI_Initialized(&on);
  if (on) return true;
  if (!force && !launched_by_mpirun()) return false;
  // Open MPI's shared-memory transport (btl vader) sends a message above
  // 4 KiB by rendezvous and a copy through the kernel (CMA), a system call
  // or more per message. A step's ghost update in a scene of 10^4 grains is
  // one such message per neighbour (35 KB on 2 ranks in bench/pour): on the
  // VM of bench/RESULTS.md (2026-12-07) it took 20 us a step, 6.5 us sent
  // eagerly. Messages up to 64 KiB are sent eagerly, unless the environment
  // sets the limit (overwrite 0: the user's or the launcher's value wins;
  // other MPI libraries ignore the variable). Larger messages keep the
  // single copy.
  setenv("OMPI_MCA_btl_vader_eager_limit", "65536", 0);
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  g_started = true;
  world();
  return true;
#else
  return false;
#endif
}

void Comm::finalize() {
#ifdef GRAINS_HAVE_MPI
  int done = 0;
  MPI_Finalized(&done);
  if (g_started && !done) MPI_Finalize();
#endif
}

#ifdef GRAINS_HAVE_MPI
namespace {
void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) {
    char msg[MPI_MAX_ERROR_STRING];
    int len = 0;
    MPI_Error_string(rc, msg, &len);
    throw std::runtime_error(std::string("MPI ") + what + " failed: " + std::string(msg, static_cast<std::size_t>(len)));
  }
}
}  // namespace
#endif

bool Comm::any(bool local) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    int in = local ? 1 : 0, out = 0;
    check(MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD), "Allreduce");
    return out != 0;
  }
#endif
  return local;
}

double Comm::max(double local) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    double out = 0;
    check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "Allreduce");
    return out;
  }
#endif
  return local;
}

double Comm::min(double local) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    double out = 0;
    check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD), "Allreduce");
    return out;
  }
#endif
  return local;
}

double Comm::sum(double local) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    double out = 0;
    check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD), "Allreduce");
    return out;
  }
#endif
  return local;
}

std::int64_t Comm::sum(std::int64_t local) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    std::int64_t out = 0;
    check(MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "Allreduce");
    return out;
  }
#endif
  return local;
}

std::int64_t Comm::max(std::int64_t local) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    std::int64_t out = 0;
    check(MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD), "Allreduce");
    return out;
  }
#endif
  return local;
}

void Comm::sum_in_place([[maybe_unused]] std::vector<double>& v) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel() && !v.empty())
    check(MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD),
          "Allreduce");
#endif
}

void Comm::sum_in_place([[maybe_unused]] std::vector<std::int64_t>& v) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel() && !v.empty())
    check(MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD),
          "Allreduce");
#endif
}

std::vector<std::int64_t> Comm::all_gather(std::int64_t local) const {
  std::vector<std::int64_t> out(static_cast<std::size_t>(size_), local);
#ifdef GRAINS_HAVE_MPI
  if (parallel()) check(MPI_Allgather(&local, 1, MPI_INT64_T, out.data(), 1, MPI_INT64_T, MPI_COMM_WORLD), "Allgather");
#endif
  return out;
}

void Comm::sendrecv_known(std::vector<Transfer>& transfers) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    static thread_local std::vector<MPI_Request> req;  // every step: no allocation after the first
    req.clear();
    for (auto& t : transfers) {
      if (t.dest == rank_ && t.src == rank_) {
        std::copy(t.send->begin(), t.send->end(), t.recv->begin());
        continue;
      }
      if (t.src >= 0) {
        req.emplace_back();
        check(MPI_Irecv(t.recv->data(), static_cast<int>(t.recv->size()), MPI_BYTE, t.src, t.tag, MPI_COMM_WORLD,
                        &req.back()),
              "Irecv");
      }
      if (t.dest >= 0) {
        req.emplace_back();
        check(MPI_Isend(t.send->data(), static_cast<int>(t.send->size()), MPI_BYTE, t.dest, t.tag, MPI_COMM_WORLD,
                        &req.back()),
              "Isend");
      }
    }
    check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "Waitall");
    return;
  }
#endif
  for (auto& t : transfers)
    if (t.src >= 0) std::copy(t.send->begin(), t.send->end(), t.recv->begin());
}

void Comm::sendrecv(std::vector<Transfer>& transfers) const {
  std::vector<std::vector<char>> size_out(transfers.size()), size_in(transfers.size());
  std::vector<Transfer> sizes;
  sizes.reserve(transfers.size());
  for (std::size_t k = 0; k < transfers.size(); ++k) {
    const auto& t = transfers[k];
    const auto bytes = static_cast<std::int64_t>(t.send->size());
    size_out[k].resize(sizeof bytes);
    std::memcpy(size_out[k].data(), &bytes, sizeof bytes);
    size_in[k].assign(sizeof bytes, 0);
    sizes.push_back({&size_out[k], t.dest, &size_in[k], t.src, t.tag});
  }
  sendrecv_known(sizes);
  for (std::size_t k = 0; k < transfers.size(); ++k) {
    auto& t = transfers[k];
    std::int64_t bytes = 0;
    if (t.src >= 0) std::memcpy(&bytes, size_in[k].data(), sizeof bytes);
    t.recv->resize(static_cast<std::size_t>(bytes));
    t.tag += 1;
  }
  sendrecv_known(transfers);
  for (auto& t : transfers) t.tag -= 1;
}

std::vector<std::vector<char>> Comm::alltoallv(const std::vector<std::vector<char>>& send) const {
  std::vector<std::vector<char>> recv(static_cast<std::size_t>(size_));
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    const auto P = static_cast<std::size_t>(size_);
    std::vector<int> sc(P), rc(P), sd(P), rd(P);
    for (std::size_t r = 0; r < P; ++r) sc[r] = static_cast<int>(send[r].size());
    check(MPI_Alltoall(sc.data(), 1, MPI_INT, rc.data(), 1, MPI_INT, MPI_COMM_WORLD), "Alltoall");
    std::vector<char> sb, rb;
    int s = 0, q = 0;
    for (std::size_t r = 0; r < P; ++r) {
      sd[r] = s;
      s += sc[r];
      rd[r] = q;
      q += rc[r];
      sb.insert(sb.end(), send[r].begin(), send[r].end());
    }
    rb.resize(static_cast<std::size_t>(q));
    check(MPI_Alltoallv(sb.data(), sc.data(), sd.data(), MPI_BYTE, rb.data(), rc.data(), rd.data(), MPI_BYTE,
                        MPI_COMM_WORLD),
          "Alltoallv");
    for (std::size_t r = 0; r < P; ++r) recv[r].assign(rb.begin() + rd[r], rb.begin() + rd[r] + rc[r]);
    return recv;
  }
#endif
  recv[0] = send[0];
  return recv;
}

std::vector<std::vector<char>> Comm::gather(const std::vector<char>& local) const {
  std::vector<std::vector<char>> out;
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    const int n = static_cast<int>(local.size());
    std::vector<int> counts(static_cast<std::size_t>(size_)), displ(static_cast<std::size_t>(size_));
    check(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "Gather");
    std::vector<char> all;
    if (root()) {
      int s = 0;
      for (std::size_t r = 0; r < counts.size(); ++r) displ[r] = s, s += counts[r];
      all.resize(static_cast<std::size_t>(s));
    }
    check(MPI_Gatherv(local.data(), n, MPI_BYTE, all.data(), counts.data(), displ.data(), MPI_BYTE, 0,
                      MPI_COMM_WORLD),
          "Gatherv");
    if (root())
      for (std::size_t r = 0; r < counts.size(); ++r)
        out.emplace_back(all.begin() + displ[r], all.begin() + displ[r] + counts[r]);
    return out;
  }
#endif
  out.push_back(local);
  return out;
}

void Comm::broadcast([[maybe_unused]] std::vector<char>& bytes) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) {
    std::int64_t n = static_cast<std::int64_t>(bytes.size());
    check(MPI_Bcast(&n, 1, MPI_INT64_T, 0, MPI_COMM_WORLD), "Bcast");
    bytes.resize(static_cast<std::size_t>(n));
    check(MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_BYTE, 0, MPI_COMM_WORLD), "Bcast");
  }
#endif
}

void Comm::barrier() const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

bool Comm::agree_error(std::string& message) const {
  if (!parallel()) return !message.empty();
  // The lowest rank with a message wins; its text goes to everyone.
  const std::int64_t mine = message.empty() ? size_ : rank_;
  std::int64_t first = mine;
#ifdef GRAINS_HAVE_MPI
  check(MPI_Allreduce(&mine, &first, 1, MPI_INT64_T, MPI_MIN, MPI_COMM_WORLD), "Allreduce");
  if (first == size_) return false;
  std::vector<char> b(message.begin(), message.end());
  std::int64_t n = static_cast<std::int64_t>(b.size());
  check(MPI_Bcast(&n, 1, MPI_INT64_T, static_cast<int>(first), MPI_COMM_WORLD), "Bcast");
  b.resize(static_cast<std::size_t>(n));
  check(MPI_Bcast(b.data(), static_cast<int>(n), MPI_BYTE, static_cast<int>(first), MPI_COMM_WORLD), "Bcast");
  message = "rank " + std::to_string(first) + ": " + std::string(b.begin(), b.end());
#endif
  return true;
}

void Comm::abort([[maybe_unused]] int code) const {
#ifdef GRAINS_HAVE_MPI
  if (parallel()) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace grains::sim
