#include "postprocess/analysis.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace grains::postprocess {

namespace fs = std::filesystem;

AnalysisResult analyze_frame(const Frame& f, const AnalysisOptions& o, const WallSet* walls) {
  AnalysisResult r;
  r.frame = f.index;
  r.time = f.time;
  r.file = f.file;
  r.n_particles = f.size();
  r.ids = f.id;
  r.ellipsoids = f.has_ellipsoids();
  r.clumps = !f.body.empty();
  if (f.size() == 0) throw std::runtime_error("frame " + std::to_string(f.index) + " has no particles");
  r.mean_diameter = f.mean_diameter();
  r.region_automatic = !o.region;
  r.region = o.region ? *o.region : auto_bulk_region(f, o.margin_diameters);
  if (!((r.region.hi - r.region.lo).array() > 0).all())
    throw std::invalid_argument("the region must have min < max on every axis");

  r.packing = packing_fraction(f, r.region, o.sampling);
  if (r.packing.exact)
    r.notes.push_back("packing fraction: exact sphere volumes in the region; contact overlaps counted twice");

  // Profile across the whole bed along the axis, over the region's extent on the other axes.
  Box span = r.region;
  const Box bounds = particle_bounds(f);
  span.lo[o.profile_axis] = bounds.lo[o.profile_axis];
  span.hi[o.profile_axis] = bounds.hi[o.profile_axis];
  r.profile = phi_profile(f, span, o.profile_axis, o.profile_bin_diameters * r.mean_diameter, o.sampling);

  const Units units = units_of(f);
  r.n_units = units.count;
  ContactOptions co;
  co.gap = o.contact_gap;
  r.contacts = find_contacts(f, co);
  r.n_contacts_total = r.contacts.size();
  r.rattler_contacts = o.rattler_contacts;
  r.rattler_rule = o.rattler_rule;
  std::vector<int> wz;
  if (walls && o.wall_contacts) {
    wz = wall_contacts(f, *walls, o.contact_gap);
    r.walls_known = true;
    for (int z : wz) r.n_wall_contacts += static_cast<std::size_t>(z);
  } else {
    r.notes.push_back("coordination: particle-particle contacts only (no walls given)");
  }
  r.coordination = coordination(f, units, r.contacts, r.region, o.rattler_contacts, o.rattler_rule, wz);

  r.forces = contact_force_distribution(f, r.contacts, r.region);
  if (!r.forces.single_material)
    r.notes.push_back("contact forces: several materials; sqrt(R*) delta^1.5 ignores their different E*");

  // RDF: every partner within r_max of a reference centre must be in the
  // sample, so references lie r_max inside the RDF box. The automatic box is
  // the whole bed below its free surface (no margin): its walls and surface
  // bound the partners, and the references stay r_max away from them.
  const Box rdf_box = o.region ? *o.region : auto_bulk_region(f, 0.0);
  const Vec3 ext = rdf_box.hi - rdf_box.lo;
  r.rdf_rmax = std::min(o.rdf_rmax_diameters * r.mean_diameter, 0.3 * ext.minCoeff());
  if (r.rdf_rmax < o.rdf_rmax_diameters * r.mean_diameter)
    r.notes.push_back("rdf: r_max reduced to 0.3 of the sample's smallest side");
  try {
    r.rdf = radial_distribution(units.centre, rdf_box, r.rdf_rmax, o.rdf_bins);
    r.rdf_region = rdf_box;
  } catch (const std::invalid_argument& e) {
    r.notes.push_back(std::string("rdf not computed: ") + e.what());
  }

  if (f.has_orientation()) {
    r.nematic = nematic_order(f, r.region, o.nematic_axis);
  } else {
    r.notes.push_back("nematic order not computed: the frame has no orientation array (spheres)");
  }
  return r;
}

namespace {

std::string vec_json(const Vec3& v) {
  std::ostringstream o;
  o << std::setprecision(10) << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  return o.str();
}

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::ofstream open_out(const fs::path& p) {
  std::ofstream o(p);
  if (!o) throw std::runtime_error("cannot write '" + p.string() + "'");
  o << std::setprecision(10);
  return o;
}

}  // namespace

std::string analysis_json(const AnalysisResult& r) {
  std::ostringstream o;
  o << std::setprecision(10);
  o << "{\n";
  o << "  \"frame\": " << r.frame << ",\n  \"time\": " << r.time << ",\n  \"file\": " << quote(r.file.string()) << ",\n";
  o << "  \"particles\": " << r.n_particles << ",\n  \"units\": " << r.n_units << ",\n";
  o << "  \"shape\": " << quote(r.ellipsoids ? "ellipsoids" : r.clumps ? "clump balls" : "spheres") << ",\n";
  o << "  \"mean_diameter\": " << r.mean_diameter << ",\n";
  o << "  \"region\": {\"min\": " << vec_json(r.region.lo) << ", \"max\": " << vec_json(r.region.hi)
    << ", \"automatic\": " << (r.region_automatic ? "true" : "false") << "},\n";
  o << "  \"packing_fraction\": {\"value\": " << r.packing.phi << ", \"error\": " << r.packing.error
    << ", \"exact\": " << (r.packing.exact ? "true" : "false") << ", \"method\": " << quote(r.packing.method) << "},\n";
  const auto& c = r.coordination;
  o << "  \"coordination\": {\"selected\": " << c.n_selected << ", \"mean\": " << c.mean_z
    << ", \"mean_without_rattlers\": " << c.mean_z_without_rattlers << ", \"rattlers\": " << c.n_rattlers
    << ", \"rattler_fraction\": " << c.rattler_fraction << ", \"rattler_rule\": "
    << quote("fewer than " + std::to_string(r.rattler_contacts) + " contacts" +
             (r.rattler_rule == RattlerRule::iterative ? ", removed iteratively" : ""))
    << ", \"particle_contacts_total\": " << r.n_contacts_total << ", \"wall_contacts_total\": " << r.n_wall_contacts
    << ", \"walls_counted\": " << (r.walls_known ? "true" : "false") << "},\n";
  const auto& fd = r.forces;
  o << "  \"contact_forces\": {\"contacts\": " << fd.n_contacts << ", \"mean_overlap\": " << fd.mean_overlap
    << ", \"max_overlap\": " << fd.max_overlap << ", \"mean_relative_overlap\": " << fd.mean_relative_overlap
    << ", \"single_material\": " << (fd.single_material ? "true" : "false")
    << ", \"force_model\": \"Hertz, f ~ sqrt(R*) overlap^1.5, normalised by its mean\"},\n";
  if (r.rdf) {
    o << "  \"rdf\": {\"box\": {\"min\": " << vec_json(r.rdf_region.lo) << ", \"max\": " << vec_json(r.rdf_region.hi)
      << "}, \"r_max\": " << r.rdf_rmax << ", \"bins\": " << r.rdf->g.size()
      << ", \"reference_particles\": " << r.rdf->n_reference << ", \"density\": " << r.rdf->density << "},\n";
  }
  if (r.nematic) {
    const auto& n = *r.nematic;
    o << "  \"nematic\": {\"S\": " << n.S << ", \"director\": " << vec_json(n.director)
      << ", \"eigenvalues\": " << vec_json(n.eigenvalues) << ", \"particles\": " << n.n << ", \"body_axis\": " << n.axis
      << ", \"isotropic_baseline\": " << n.isotropic_baseline << "},\n";
  }
  o << "  \"profile\": {\"axis\": " << quote(std::string(1, "xyz"[r.profile.axis])) << ", \"slabs\": " << r.profile.phi.size()
    << ", \"exact\": " << (r.profile.exact ? "true" : "false") << "},\n";
  o << "  \"notes\": [";
  for (std::size_t k = 0; k < r.notes.size(); ++k) o << (k ? ", " : "") << quote(r.notes[k]);
  o << "]\n}\n";
  return o.str();
}

std::vector<fs::path> write_analysis(const AnalysisResult& r, const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create '" + dir.string() + "': " + ec.message());
  std::vector<fs::path> files;
  {
    files.push_back(dir / "analysis.json");
    auto o = open_out(files.back());
    o << analysis_json(r);
  }
  {
    files.push_back(dir / "phi_profile.csv");
    auto o = open_out(files.back());
    const char ax = "xyz"[r.profile.axis];
    o << ax << "_lo," << ax << "_hi,phi,phi_error\n";
    for (std::size_t k = 0; k < r.profile.phi.size(); ++k)
      o << r.profile.lo[k] << "," << r.profile.hi[k] << "," << r.profile.phi[k] << "," << r.profile.error[k] << "\n";
  }
  if (r.rdf) {
    files.push_back(dir / "rdf.csv");
    auto o = open_out(files.back());
    o << "r,r_over_d,g\n";
    for (std::size_t k = 0; k < r.rdf->g.size(); ++k)
      o << r.rdf->r[k] << "," << r.rdf->r[k] / r.mean_diameter << "," << r.rdf->g[k] << "\n";
  }
  {
    files.push_back(dir / "coordination.csv");
    auto o = open_out(files.back());
    o << "z,count,fraction\n";
    const auto& h = r.coordination.histogram;
    for (std::size_t z = 0; z < h.size(); ++z)
      o << z << "," << h[z] << ","
        << (r.coordination.n_selected ? static_cast<double>(h[z]) / static_cast<double>(r.coordination.n_selected) : 0.0)
        << "\n";
  }
  {
    files.push_back(dir / "contact_forces.csv");
    auto o = open_out(files.back());
    o << "f_over_mean,pdf\n";
    for (std::size_t k = 0; k < r.forces.pdf.size(); ++k) o << r.forces.centre[k] << "," << r.forces.pdf[k] << "\n";
  }
  {
    files.push_back(dir / "contacts.csv");
    auto o = open_out(files.back());
    o << "id_i,id_j,overlap,radius_eff,f_over_mean,nx,ny,nz,px,py,pz\n";
    for (std::size_t s = 0; s < r.forces.selected.size(); ++s) {
      const auto& c = r.contacts[r.forces.selected[s]];
      o << r.ids[c.i] << "," << r.ids[c.j] << "," << c.overlap << "," << c.radius << "," << r.forces.f_over_mean[s] << ","
        << c.normal[0] << "," << c.normal[1] << "," << c.normal[2] << "," << c.point[0] << "," << c.point[1] << ","
        << c.point[2] << "\n";
    }
  }
  return files;
}

std::string analysis_summary(const AnalysisResult& r) {
  std::ostringstream o;
  o << std::setprecision(4);
  o << "frame " << r.frame << " (t = " << r.time << " s): " << r.n_particles << " particles";
  if (r.clumps) o << " in " << r.n_units << " clumps";
  o << ", mean diameter " << r.mean_diameter << " m\n";
  o << "region " << (r.region_automatic ? "(automatic bulk) " : "") << "[" << r.region.lo.transpose() << "] - ["
    << r.region.hi.transpose() << "]\n";
  o << std::setprecision(5);
  o << "packing fraction " << r.packing.phi;
  if (!r.packing.exact) o << " +- " << r.packing.error << " (1 sigma)";
  o << "   [" << r.packing.method << "]\n";
  const auto& c = r.coordination;
  o << "coordination " << c.mean_z << " (" << c.n_selected << " particles), without rattlers "
    << c.mean_z_without_rattlers << ", rattlers " << c.n_rattlers << " (" << 100 * c.rattler_fraction << " %)\n";
  o << "contacts " << r.forces.n_contacts << " in region, mean overlap " << r.forces.mean_overlap << " m ("
    << 100 * r.forces.mean_relative_overlap << " % of 2R*)\n";
  if (r.rdf) {
    const auto peaks = rdf_peaks(*r.rdf, 1.5);
    o << "rdf: r_max " << r.rdf_rmax << " m, " << r.rdf->n_reference << " reference particles";
    if (!peaks.empty()) o << ", first peak at r/d = " << peaks[0] / r.mean_diameter;
    o << "\n";
  }
  if (r.nematic)
    o << "nematic S " << r.nematic->S << " (isotropic baseline for this N: " << r.nematic->isotropic_baseline
      << "), director [" << r.nematic->director.transpose() << "]\n";
  for (const auto& n : r.notes) o << "note: " << n << "\n";
  return o.str();
}

}  // namespace grains::postprocess
