#pragma once
// The registry of normal laws: the one place a normal law is registered.
// Everything else (the pipeline's dispatch, the pair table's calibration,
// `grains docs`, the case parser's contact.model and contact.<law> keys,
// the time-step check and the property tests) walks this list.
//
// A normal law is a struct with
//   name, tangential_name          case-file names of the law and of the tangential spring it pairs with
//   summary(), keys()              its documentation and its own keys (contact.<name>: {...}), in
//                                  LawValues order, with units, defaults and ranges
//   check(values)                  "" or what is wrong with the keys given (defaults filled in)
//   prepare(PairParams&, values)   per material pair at set-up: calibration into PairParams
//   evaluate(d, d_dot, R*, m*, p)  its normal state of one contact (normal_state.hpp) (inlined into every contact loop)
//   step_scale(pairs, grains)      the time scale the time step is checked against
//   examples()                     valid values, one per way of giving the law (the property tests run
//                                  every law with each)
//   adhesive (optional)            true: it reads PairParams::work_of_adhesion (materials' surface_energy)
//   history_size, engaged(d, R*, p, on), reach(R*, p), reach(pairs, R)   (optional)
//                                  a law whose contacts outlive touching (JKR): one double of state per
//                                  contact, whether the pair is in contact at overlap d (updating it), and
//                                  how far below zero overlap a contact may hold (lists and ghosts reach it)
// (docs/architecture.md: how to add one).
#include "sim/laws/normal_dmt.hpp"
#include "sim/laws/normal_hertz.hpp"
#include "sim/laws/normal_jkr.hpp"
#include "sim/laws/normal_linear.hpp"
#include "sim/registry.hpp"

namespace grains::sim {

using NormalLaws = TypeList<HertzNormal, LinearNormal, DmtNormal, JkrNormal>;  // the first is the default

/// Whether a normal law acts on the pairs' work of adhesion (static
/// constexpr bool adhesive = true); the others refuse a case that gives one.
template <class N>
constexpr bool is_adhesive() {
  if constexpr (requires { N::adhesive; })
    return N::adhesive;
  else
    return false;
}

/// The doubles of contact state a normal law keeps (after the tangential and
/// rolling springs'): 0 for laws whose contact is simply "overlap > 0".
template <class N>
constexpr int normal_history() {
  if constexpr (requires { N::history_size; })
    return N::history_size;
  else
    return 0;
}

}  // namespace grains::sim
