#pragma once
// Clump files (YAML). Layout, SI units:
//
//   grains_clump: 1                  # format version
//   units: SI
//   density: 1000                    # kg/m^3
//   mass: ...                        # kg, of the union of balls
//   volume: ...                      # m^3, of the union of balls
//   volume_integration_bound: ...    # m^3, strict bound on the integration error
//   inertia_principal: [I1, I2, I3]  # kg m^2, about the centre of mass, ascending
//   centre_of_mass_mesh_frame: [x, y, z]
//   body_axes_mesh_frame: [[..], [..], [..]]  # row a = body axis a in mesh coordinates
//   decomposition: {...}             # method, grid, mu, epsilon, n1, n2, n3, measured errors, times
//   balls:                           # body frame: x, y, z, r
//     - [x, y, z, r]
//
// load_clump_yaml reads balls, density, mass, volume, inertia and frame; the
// decomposition metadata is read back where present.

#include "contact/clump/clump_template.hpp"

#include <ostream>
#include <stdexcept>
#include <string>

namespace grains::clump {

class ClumpFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

void write_clump_yaml(const ClumpTemplate& clump, std::ostream& out);
void write_clump_yaml(const ClumpTemplate& clump, const std::string& path);
ClumpTemplate load_clump_yaml(const std::string& path);

}  // namespace grains::clump
