// Fuzz target: a mesh reader and the validation after it (built once per
// format: GRAINS_FUZZ_EXT selects the reader by file extension). Any input
// must end in a mesh or a MeshError; anything else is a bug. The readers
// take paths, so each input is written to a file in /dev/shm first.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "io/mesh/mesh_error.hpp"
#include "io/mesh/mesh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/dev/shm/grains_fuzz_" + std::to_string(getpid()) + GRAINS_FUZZ_EXT;
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)grains::mesh::load_mesh(path);
  } catch (const grains::mesh::MeshError&) {
  }
  return 0;
}
