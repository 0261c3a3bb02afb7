#pragma once
// Distribution of normal contact forces, from the contacts recomputed from
// positions and shapes (contacts.hpp). The output files hold only each
// particle's *net* force (force point array), which in a static packing is
// close to its weight and says nothing about individual contacts, so it is not
// used. Instead each contact's normal force is rebuilt from its overlap with
// the Hertz law, up to the material constant:
//     f_n = (4/3) E* sqrt(R*) delta^(3/2)  ~  sqrt(R*) delta^(3/2).
// Normalised by its mean over the contacts in the region, f_n / <f_n> is the
// exact Hertz value when all particles share one material (E* cancels); with
// several materials of different stiffness it is a proxy (the report says so).
// Contact damping forces are not included (the frame holds no relative velocity
// per contact; in a settled packing they vanish).
#include <vector>

#include "postprocess/contacts.hpp"

namespace grains::postprocess {

struct ContactForceDistribution {
  std::size_t n_contacts = 0;       // contacts with a positive overlap and their point in the region
  double mean_overlap = 0, max_overlap = 0;  // m
  double mean_relative_overlap = 0;  // delta / (2 R*), i.e. relative to a reduced diameter
  double bin = 0.1;                  // width in f / <f>
  std::vector<double> centre, pdf;   // P(f / <f>), normalised to unit area
  std::vector<double> f_over_mean;   // per selected contact, same order as `selected`
  std::vector<std::size_t> selected; // indices into the contact list
  bool single_material = true;
};

ContactForceDistribution contact_force_distribution(const Frame& f, const std::vector<Contact>& contacts,
                                                    const Box& region, double bin = 0.1, double f_max = 6.0);

}  // namespace grains::postprocess
