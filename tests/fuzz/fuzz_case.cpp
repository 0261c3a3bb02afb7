// Fuzz target: the case-file parser and validator. Any input must end in a
// parsed case or a CaseError (file:line:column messages); anything else
// (a crash, a sanitizer report, another exception) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/case/case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)grains::io::parse_case(text, "fuzz.yaml", {}, "/nonexistent");
  } catch (const grains::io::CaseError&) {
  } catch (const grains::sim::SetupError&) {
  }
  return 0;
}
