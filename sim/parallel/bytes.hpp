#pragma once
// Trivially copyable values into and out of a byte buffer: the message
// format of the exchanges, gathers and insertions over MPI ranks.
#include <cstring>
#include <vector>

namespace grains::sim::bytes {

template <class T>
void put(std::vector<char>& b, const T& v) {
  const auto* c = reinterpret_cast<const char*>(&v);
  b.insert(b.end(), c, c + sizeof(T));
}

template <class T>
T take(const char*& r) {
  T v;
  std::memcpy(reinterpret_cast<char*>(&v), r, sizeof(T));
  r += sizeof(T);
  return v;
}

}  // namespace grains::sim::bytes
