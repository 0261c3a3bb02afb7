#pragma once
// Everything `grains analyze` computes for one frame, and the files it writes:
//   analysis.json      the scalar results, the region and the methods used
//   phi_profile.csv    phi in slabs along an axis (with error bars when sampled)
//   rdf.csv            g(r) of the centres (in the region, or the whole bed when automatic)
//   coordination.csv   histogram of contacts per particle in the region
//   contact_forces.csv P(f/<f>) of Hertz normal forces rebuilt from overlaps
//   contacts.csv       every contact with its point in the region
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "postprocess/contact_forces.hpp"
#include "postprocess/contacts.hpp"
#include "postprocess/frame.hpp"
#include "postprocess/frame_packing.hpp"
#include "postprocess/nematic_order.hpp"
#include "postprocess/rdf.hpp"
#include "postprocess/walls.hpp"

namespace grains::postprocess {

struct AnalysisOptions {
  std::optional<Box> region;       // default: auto_bulk_region
  double margin_diameters = 2.0;   // for the automatic region
  int rattler_contacts = 4;        // rattler: fewer contacts than this
  RattlerRule rattler_rule = RattlerRule::once;
  bool wall_contacts = true;       // count contacts with the frame's walls (walls.vtp)
  double contact_gap = 0.0;        // m; pairs this close count as contacts
  double rdf_rmax_diameters = 5.0;
  int rdf_bins = 200;
  int profile_axis = 2;
  double profile_bin_diameters = 0.5;
  int nematic_axis = -1;           // body axis; -1 picks the shape's axis
  SamplingOptions sampling;
};

struct AnalysisResult {
  std::size_t frame = 0;
  double time = 0;
  std::filesystem::path file;
  std::size_t n_particles = 0, n_units = 0;
  bool ellipsoids = false, clumps = false;
  double mean_diameter = 0;
  Box region;
  bool region_automatic = false;
  PackingEstimate packing;
  PhiProfile profile;
  std::size_t n_contacts_total = 0;
  Coordination coordination;
  int rattler_contacts = 4;
  RattlerRule rattler_rule = RattlerRule::once;
  std::size_t n_wall_contacts = 0;
  bool walls_known = false;
  ContactForceDistribution forces;
  std::vector<Contact> contacts;
  std::vector<std::int64_t> ids;  // particle ids of the frame (contacts.csv)
  std::optional<Rdf> rdf;
  double rdf_rmax = 0;
  Box rdf_region;  // the sample the RDF's references were taken from
  std::optional<NematicOrder> nematic;
  std::vector<std::string> notes;  // what could not be computed and why, caveats
};

/// `walls` (from read_walls) adds particle-wall contacts to the coordination.
AnalysisResult analyze_frame(const Frame& f, const AnalysisOptions& o = {}, const WallSet* walls = nullptr);

/// Writes the files listed above into `dir` (created if needed). Returns their paths.
std::vector<std::filesystem::path> write_analysis(const AnalysisResult& r, const std::filesystem::path& dir);

/// analysis.json text.
std::string analysis_json(const AnalysisResult& r);

/// A short human-readable summary.
std::string analysis_summary(const AnalysisResult& r);

}  // namespace grains::postprocess
