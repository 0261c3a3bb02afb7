#pragma once
// Registries of compile-time types (laws by slot, sim/laws/*_laws.hpp; wall
// kinds, sim/walls/wall_kinds.hpp): a
// type list that dispatch, `grains docs`, the case parser and the property
// tests all walk, so a law is named and described in one place and costs no
// virtual call per contact.
#include <string>
#include <string_view>
#include <vector>

namespace grains::sim {

template <class... Ts>
struct TypeList {
  static constexpr int size = sizeof...(Ts);
};

/// f.template operator()<T>() for every T of the list, in order.
template <class... Ts, class F>
void for_each_type(TypeList<Ts...>, F&& f) {
  (f.template operator()<Ts>(), ...);
}

/// f.template operator()<T>() for the T whose T::name is `name`; false when
/// no type of the list has that name.
template <class... Ts, class F>
bool with_type_named(TypeList<Ts...>, std::string_view name, F&& f) {
  bool found = false;
  ((!found && name == std::string_view(Ts::name) ? (f.template operator()<Ts>(), found = true) : false), ...);
  return found;
}

/// The names of the list's types, in order.
template <class... Ts>
std::vector<std::string> type_names(TypeList<Ts...>) {
  return {std::string(Ts::name)...};
}

}  // namespace grains::sim
