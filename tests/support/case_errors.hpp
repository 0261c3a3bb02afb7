#pragma once
// The messages of a case that must fail (parse or set-up), for the tests of
// malformed input; a case that is accepted is a test failure.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"

namespace grains::test {

inline std::string errors_of(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  try {
    (void)io::make_simulation(io::parse_case(yaml, "case.yaml", sets));
  } catch (const io::CaseError& e) {
    return e.what();
  } catch (const sim::SetupError& e) {
    return e.what();
  }
  ADD_FAILURE() << "case was accepted:\n" << yaml;
  return "";
}

}  // namespace grains::test
