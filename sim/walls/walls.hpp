#pragma once
// The walls of a scene, kept by kind (wall_kinds.hpp), each optionally moving
// with a prescribed constant velocity. A wall has a material (for the pair
// table) and, when the contact law keeps history, slots in every particle's
// wall-history field. Walls have one index across kinds ("wall w"), in the
// registry's kind order: near lists and output use it.
#include <cstddef>
#include <string>
#include <tuple>
#include <vector>

#include "sim/walls/wall_kinds.hpp"

namespace grains::sim {

template <class List>
struct WallVectors;
template <class... Ks>
struct WallVectors<TypeList<Ks...>> {
  using type = std::tuple<std::vector<Ks>...>;
};

struct Walls {
  typename WallVectors<WallKinds>::type by_kind;

  template <class K>
  std::vector<K>& of() {
    return std::get<std::vector<K>>(by_kind);
  }
  template <class K>
  const std::vector<K>& of() const {
    return std::get<std::vector<K>>(by_kind);
  }
  template <class K>
  void add(const K& w) {
    of<K>().push_back(w);
  }

  /// f(wall, w) for every wall, w its index across kinds.
  template <class F>
  void for_each(F&& f) {
    std::size_t w = 0;
    std::apply([&](auto&... v) { ((for_vector(v, f, w)), ...); }, by_kind);
  }
  template <class F>
  void for_each(F&& f) const {
    std::size_t w = 0;
    std::apply([&](const auto&... v) { ((for_vector(v, f, w)), ...); }, by_kind);
  }
  std::size_t count() const {
    std::size_t n = 0;
    for_each([&](const auto&, std::size_t) { ++n; });
    return n;
  }
  /// "2 plane(s), 1 cylinder(s)": the count of every registered kind.
  std::string describe() const;
  /// Largest distance any wall's surface has moved in the last time t.
  double max_displacement(double t) const;
  /// A bound on the speed of any wall's surface at any time (0: no wall moves).
  double max_speed() const;
  void advance(double dt);
  /// The box the infinite planes bound along axis d: the highest floor (a
  /// plane with normal +e_d) and the lowest ceiling (normal -e_d); false
  /// when there is not one of each.
  bool facing_planes(int d, double& lo, double& hi) const;
  /// Whether any wall has a controlled motion (walls[].control).
  bool controlled() const {
    bool any = false;
    for_each([&](const auto& w, std::size_t) { any = any || w.control.active(); });
    return any;
  }

 private:
  template <class V, class F>
  static void for_vector(V& v, F& f, std::size_t& w) {
    for (auto& x : v) f(x, w++);
  }
};

}  // namespace grains::sim
