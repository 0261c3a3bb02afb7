#include "io/case/case.hpp"
#include "io/case/clump_shapes.hpp"
#include "io/mesh/mesh_reader.hpp"
#include "sim/laws/normal_laws.hpp"
#include "sim/walls/wall_kinds.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace grains::io {

void register_checkpoint_docs();  // io/checkpoint/checkpoint_docs.cpp

using sim::EffectDoc;
using sim::Vec3;

void register_io_docs() {
  static const bool once = [] {
    using K = sim::KeyType;
    const double inf = std::numeric_limits<double>::infinity();
    sim::register_effect_doc(
        {"output", "output: {...}",
         "What a run writes into its output folder (grains run -o DIR): VTK frames (particles .vtu, walls .vtp, "
         "a .pvd series each), a progress line on stderr and summary.json.",
         {sim::key("every", K::Number, "simulated time between frames (first and last frame always written)")
              .si("s").in(0, inf, true),
          sim::key("every_steps", K::Integer, "steps between frames (instead of every)").in(1, 1e15),
          sim::key("vtk", K::Bool, "write VTK frames").def("true"),
          sim::key("progress", K::Bool, "print a progress line to stderr (also -q)").def("true"),
          sim::key("progress_interval", K::Number, "wall-clock time between progress lines").def("2").si("s").in(0, inf),
          sim::key("solid_fraction", K::Map, "solid-fraction field as VTK image data (see output.solid_fraction)"),
          sim::key("mass", K::Map, "grains and their mass against time in mass.csv, e.g. silo discharge (see output.mass)"),
          sim::key("wall_loads", K::Map, "force and torque on each wall against time in wall_loads.csv (see output.wall_loads)"),
          sim::key("stress", K::Map, "stress tensor, solid fraction and velocity of a region and their profiles against time (see output.stress)")}});
    sim::register_effect_doc(
        {"output.stress", "output: {stress: {...}}",
         "The stress tensor of a region, contact and kinetic parts, with its solid fraction and mean velocity, one "
         "row per interval and at the last step in OUTDIR/stress.csv (step, time_s, volume_m3, grains, solid_fraction, vx..vz_mps, the "
         "total stress sxx..syz_Pa, its kinetic part kxx..kyz_Pa, pressure_Pa); with a profile, the same per bin "
         "along an axis in OUTDIR/profile.csv (bin, position_m of its centre, ...). Compressive stress > 0. "
         "Contact part: Love-Weber, (1/V) sum over contacts of w F (x) b, the branch b joining the two centres (from "
         "a wall's contact point to the centre), w the fraction of the branch inside the region or bin (so a bin's "
         "stress is the method-of-planes stress averaged over it: in a static bed sigma_zz is the weight above per "
         "area, however thin the bins); measured on the step itself by the force stages, which do nothing for it "
         "on other steps. Kinetic part: "
         "sum m (v - u)(v - u) / V, u the mean velocity of the grain's bin (of the region without a profile). "
         "Solid fraction: per bin the exact volume of each sphere inside the slab (an ellipsoid as its "
         "equal-volume sphere), of the region the grains whose centre is in it. The region is by default the box: "
         "along each axis the periodic domain, else the gap between the infinite planes facing each other "
         "(measured each time: a servo box), else the domain. At the end summary.json has the means over the rows "
         "from average_after on and OUTDIR/profile_mean.csv the mean profile (both read back from the files, so a "
         "restarted run's means cover all of it). Summed over the ranks. Verlet only; not with clumps.",
         {sim::key("every", K::Number, "simulated time between rows; default the VTK frame cadence").si("s").in(0, inf, true),
          sim::key("every_steps", K::Integer, "steps between rows (instead of every)").in(1, 1e15),
          sim::key("average_after", K::Number, "the means are over rows at or after this time").def(0.0).si("s").in(0, inf),
          sim::key("region", K::Map, "{min: [x, y, z], max: [x, y, z]}: the region measured; default the box"),
          sim::key("profile_axis", K::String, "the axis of the profile").one_of({"x", "y", "z"}),
          sim::key("bins", K::Integer, "profile bins along profile_axis across the region").in(1, 1e6)}});
    sim::register_effect_doc(
        {"output.wall_loads", "output: {wall_loads: {...}}",
         "One row per wall and interval in OUTDIR/wall_loads.csv: step, time_s, wall, name, kind, the force the "
         "particles exert on the wall (fx_N, fy_N, fz_N), the torque about its load point (tx_Nm, ty_Nm, tz_Nm: a "
         "mesh wall's torque_point, by default on its rotation axis; another wall's position) and, for a mesh wall, "
         "the torque about its rotation axis (axial_torque_Nm: what a drum's or a mixer's drive supplies is minus "
         "it), the wall's position (px_m, py_m, pz_m: a plane's point, a mesh's offset, a cylinder's base) and, for "
         "a controlled wall (walls.control), its speed towards the grains, the area its stress acts on and that "
         "normal stress (speed_mps, area_m2, stress_Pa; empty for other walls). summary.json (stage_details) has each wall's mean over the rows from average_after on, and its last "
         "row. Measured only when asked: without this block no wall stage sums loads.",
         {sim::key("every", K::Number, "simulated time between rows; default the VTK frame cadence")
              .si("s").in(0, inf, true),
          sim::key("every_steps", K::Integer, "steps between rows (instead of every)").in(1, 1e15),
          sim::key("average_after", K::Number, "the summary's mean is over rows at or after this time").def(0.0).si("s").in(0, inf)}});
    sim::register_effect_doc(
        {"output.mass", "output: {mass: {...}}",
         "One row per interval in OUTDIR/mass.csv: step, time_s, grains and mass_kg (spheres, ellipsoids, whole "
         "clumps by their centre of mass) on the front side of a plane (the whole domain without one), and "
         "lost_particles, removed so far because they left the domain. With the plane through a silo's orifice, "
         "the discharge rate is minus the slope of mass_kg against time.",
         {sim::key("every", K::Number, "simulated time between rows; default the VTK frame cadence")
              .si("s").in(0, inf, true),
          sim::key("every_steps", K::Integer, "steps between rows (instead of every)").in(1, 1e15),
          sim::key("point", K::Vec3, "a point on the counting plane (give with normal)").si("m"),
          sim::key("normal", K::Vec3, "the plane's normal; grains on this side count (normalised for you)")}});
    sim::register_effect_doc(
        {"output.solid_fraction", "output: {solid_fraction: {...}}",
         "The coarse-grained solid fraction on a regular grid over the domain (NUFFT of the particles, a Gaussian "
         "of width `smoothing`), written as frames/solid_fraction_*.vti with a solid_fraction.pvd series. "
         "Ellipsoids count as equal-volume spheres; overlapping clump balls count twice.",
         {sim::key("spacing", K::Number, "grid spacing").req().si("m").in(0, inf, true),
          sim::key("smoothing", K::Number, "Gaussian width; default the spacing").si("m").in(0, inf, true),
          sim::key("tolerance", K::Number, "absolute accuracy of the field values").def("1e-4").in(1e-12, 1e-2),
          sim::key("every", K::Number, "simulated time between fields; default the VTK frame cadence")
              .si("s").in(0, inf, true),
          sim::key("every_steps", K::Integer, "steps between fields (instead of every)").in(1, 1e15)}});
    register_checkpoint_docs();
    return true;
  }();
  (void)once;
}

namespace {

const EffectDoc& doc(const std::string& name) {
  const EffectDoc* d = sim::find_effect_doc(name);
  if (!d) throw std::logic_error("no documentation for effect " + name);
  return *d;
}

std::string idx(const std::string& list, std::size_t i) { return list + "[" + std::to_string(i) + "]"; }

class CaseParser {
 public:
  CaseParser(Case& c, Validator& v) : c_(c), v_(v) {}

  void parse() {
    const YAML::Node& root = c_.root;
    if (!v_.check_map(root, doc("case"), "")) return;
    parse_domain(root["domain"]);
    auto& sc = c_.scene;
    if (root["gravity"]) sc.gravity = v_.vec3(root, doc("case"), "gravity", "");
    parse_materials(root["materials"]);
    parse_contact(root["contact"]);
    check_adhesion();
    parse_particles(root["particles"]);
    if (!root["particles"] && !root["insert"])
      v_.error(root, "", "missing required key 'particles' (particle sets (see particles)); a case needs particles, or "
                         "insert[] to add grains during the run");
    parse_walls(root["walls"]);
    parse_time(root["time"]);
    parse_neighbor(root["neighbor"]);
    parse_parallel(root["parallel"]);
    parse_growth(root["radius_growth"]);
    parse_insert(root["insert"]);
    parse_output(root["output"]);
    parse_checkpoint(root["checkpoint"]);
  }

 private:
  void parse_domain(const YAML::Node& n) {
    if (!n) return;
    const auto& d = doc("domain");
    if (!v_.check_map(n, d, "domain")) return;
    auto& dom = c_.scene.domain;
    dom.lo = v_.vec3(n, d, "min", "domain");
    dom.hi = v_.vec3(n, d, "max", "domain");
    if (n["min"] && n["max"] && ((dom.hi - dom.lo).array() <= 0).any())
      v_.error(n["max"], "domain", "max must exceed min in every coordinate");
    dom.periodic = v_.bool3(n, d, "periodic", "domain");
    if (const YAML::Node sh = n["shear"]) {
      const auto& sd = doc("domain.shear");
      const std::string ctx = "domain.shear";
      if (!v_.check_map(sh, sd, ctx)) return;
      auto axis = [&](const char* k) {
        const std::string a = v_.string(sh, sd, k, ctx, "");
        return a == "x" ? 0 : a == "y" ? 1 : a == "z" ? 2 : -1;
      };
      const int f = axis("flow"), g = axis("gradient");
      dom.shear.rate = v_.number(sh, sd, "rate", ctx, 0);
      if (sh["rate"] && dom.shear.rate == 0) v_.error(sh["rate"], ctx, "rate must not be 0 (no shear: leave shear out)");
      c_.scene.shear_profile = v_.boolean(sh, sd, "initial_profile", ctx, true);
      dom.shear.pressure = v_.number(sh, sd, "pressure", ctx, 0);
      if (sh["pressure"] && !(dom.shear.pressure > 0))
        v_.error(sh["pressure"], ctx, "pressure must be compressive, > 0 (the normal stress the cell holds across "
                                      "the gradient): got " + sh["pressure"].Scalar());
      dom.shear.gain = v_.number(sh, sd, "gain", ctx, 0.1);
      dom.shear.max_dilation = v_.number(sh, sd, "max_dilation", ctx, 0);
      for (const char* k : {"gain", "max_dilation"})
        if (sh[k] && !sh["pressure"]) v_.error(sh[k], ctx, std::string(k) + " goes with pressure (the cell's servo)");
      c_.scene.shear_where = v_.where(sh);
      if (f < 0 || g < 0) return;
      if (f == g) {
        v_.error(sh["gradient"], ctx, "flow and gradient must be different axes");
        return;
      }
      for (const int a : {f, g})
        if (!dom.periodic[a]) {
          v_.error(sh[a == f ? "flow" : "gradient"], ctx,
                   std::string("a shear rate needs periodic ") + "xyz"[a] + " (the " + (a == f ? "flow" : "gradient") +
                       " axis): the domain is not periodic along it; set domain.periodic");
          return;
        }
      dom.shear.flow = f, dom.shear.gradient = g;
    }
  }

  void parse_parallel(const YAML::Node& n) {
    if (!n) return;
    const auto& d = doc("parallel");
    if (!v_.check_map(n, d, "parallel")) return;
    auto& par = c_.scene.parallel;
    par.where = v_.where(n);
    if (n["deterministic"]) par.deterministic = v_.boolean(n, d, "deterministic", "parallel", false);
    par.balance_threshold = v_.number_or_default(n, d, "balance_threshold", "parallel");
    if (n["decomposition"]) {
      const auto v = v_.vec3(n, d, "decomposition", "parallel", sim::Vec3::Zero());
      for (int k = 0; k < 3; ++k) {
        if (v[k] < 1 || v[k] != std::floor(v[k])) {
          v_.error(n["decomposition"], "parallel", "decomposition must be 3 positive integers [nx, ny, nz] whose "
                                                   "product is the number of MPI ranks");
          break;
        }
        par.dims[k] = static_cast<int>(v[k]);
      }
      par.where = v_.where(n["decomposition"]);
    }
  }

  void parse_materials(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsSequence() || n.size() == 0) {
      v_.error(n, "materials", "expected a non-empty list of materials");
      return;
    }
    const auto& d = doc("materials");
    for (std::size_t i = 0; i < n.size(); ++i) {
      const auto ctx = idx("materials", i);
      const YAML::Node m = n[i];
      if (!v_.check_map(m, d, ctx)) continue;
      sim::Material mat;
      mat.name = v_.string(m, d, "name", ctx);
      mat.density = v_.number(m, d, "density", ctx, 1);
      mat.youngs_modulus = v_.number(m, d, "youngs_modulus", ctx, 1);
      mat.poisson_ratio = v_.number(m, d, "poisson_ratio", ctx, 0.3);
      // Optional keys: their defaults are the declared ones (law_docs.cpp).
      mat.restitution = v_.number_or_default(m, d, "restitution", ctx);
      mat.friction = v_.number_or_default(m, d, "friction", ctx);
      mat.rolling_friction = v_.number_or_default(m, d, "rolling_friction", ctx);
      mat.cohesion = v_.number_or_default(m, d, "cohesion_energy_density", ctx);
      mat.surface_energy = v_.number_or_default(m, d, "surface_energy", ctx);
      if (mat.surface_energy > 0 && adhesion_where_.empty()) adhesion_where_ = v_.where(m["surface_energy"]);
      if (!m["name"]) continue;  // reported as a missing required key
      if (material_index_.count(mat.name)) v_.error(m["name"], ctx, "material '" + mat.name + "' is defined twice");
      material_index_[mat.name] = static_cast<int>(c_.scene.materials.size());
      c_.scene.materials.push_back(mat);
    }
  }

  int material(const YAML::Node& map, const EffectDoc& d, const std::string& ctx) {
    const YAML::Node n = map["material"];
    if (!n) return 0;
    const std::string name = v_.string(map, d, "material", ctx);
    auto it = material_index_.find(name);
    if (it != material_index_.end()) return it->second;
    std::vector<std::string> names;
    for (const auto& m : c_.scene.materials) names.push_back(m.name);
    const std::string guess = closest(name, names);
    std::string list;
    for (const auto& s : names) list += (list.empty() ? "" : ", ") + s;
    v_.error(n, ctx, "unknown material '" + name + "'" + (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
                         " defined materials: " + list);
    return 0;
  }

  static sim::SlotChoice slot(const std::string& s) {
    if (s == "auto") return sim::SlotChoice::Auto;
    if (s == "none") return sim::SlotChoice::None;
    return sim::SlotChoice::On;
  }

  // The values of a normal law's own keys given in `map` (NaN where absent).
  template <class N>
  sim::LawValues law_values(const YAML::Node& map, const std::string& ctx) {
    sim::LawValues v;
    const auto& d = doc(std::string("contact.") + N::name);
    if (!v_.check_map(map, d, ctx)) return v;
    for (std::size_t k = 0; k < d.keys.size(); ++k) {
      const auto& spec = d.keys[k];
      if (!map[spec.name]) continue;
      v[static_cast<int>(k)] = spec.type == sim::KeyType::Bool ? (v_.boolean(map, d, spec.name, ctx) ? 1.0 : 0.0)
                                                                : v_.number(map, d, spec.name, ctx);
    }
    return v;
  }

  // The normal law's key maps present in `n` (contact or a pair override):
  // those of the chosen law are read into `out`; another law's map is an error.
  void parse_law_maps(const YAML::Node& n, const std::string& ctx, sim::LawValues& out) {
    const std::string& model = c_.scene.normal.name;
    sim::for_each_type(sim::NormalLaws{}, [&]<class N>() {
      const YAML::Node m = n[N::name];
      if (!m || N::keys().empty()) return;
      if (model != N::name) {
        v_.error(m, ctx, std::string("keys of the ") + N::name + " law given, but contact.model is " + model +
                             "; set contact.model: " + N::name + " or remove them");
        return;
      }
      out = law_values<N>(m, ctx + "." + N::name);
    });
  }

  // The chosen law's check of its values (defaults filled in), reported at `at`.
  void check_law_values(const sim::LawValues& given, const YAML::Node& at, const std::string& ctx) {
    sim::with_type_named(sim::NormalLaws{}, c_.scene.normal.name, [&]<class N>() {
      const std::string e = N::check(given);
      if (!e.empty()) v_.error(at, ctx, std::string("contact.model: ") + N::name + ": " + e);
    });
  }

  // Adhesion given to a normal law that has none is an error, not ignored.
  void check_adhesion() {
    if (adhesion_where_.empty()) return;
    bool adhesive = false;
    std::string laws;
    sim::for_each_type(sim::NormalLaws{}, [&]<class N>() {
      if (!sim::is_adhesive<N>()) return;
      laws += std::string(laws.empty() ? "" : " or ") + N::name;
      if (c_.scene.normal.name == N::name) adhesive = true;
    });
    if (!adhesive)
      v_.error_at(adhesion_where_, "adhesion (surface_energy or work_of_adhesion > 0) needs an adhesive normal law, "
                                   "contact.model: " + laws + "; model " + c_.scene.normal.name +
                                   " has no adhesion and would ignore it");
  }

  void parse_contact(const YAML::Node& n) {
    // The normal law's defaults apply whether or not the section is there.
    auto defaults = [&] {
      sim::LawValues v;
      sim::with_type_named(sim::NormalLaws{}, c_.scene.normal.name, [&]<class N>() { v = sim::law_defaults<N>(); });
      return v;
    };
    if (!n) {
      c_.scene.normal.values = defaults();
      return;
    }
    const auto& d = doc("contact");
    if (!v_.check_map(n, d, "contact")) return;
    c_.scene.normal.name = v_.string(n, d, "model", "contact", d.find("model")->default_value);
    c_.scene.normal_where = v_.where(n["model"] ? n["model"] : n);
    sim::LawValues given;
    parse_law_maps(n, "contact", given);
    c_.scene.normal.values = given.over(defaults());
    check_law_values(c_.scene.normal.values, n[c_.scene.normal.name] ? n[c_.scene.normal.name] : n, "contact");
    const std::string tangential = v_.string(n, d, "tangential", "contact", "auto");
    c_.scene.tangential = slot(tangential);
    sim::with_type_named(sim::NormalLaws{}, c_.scene.normal.name, [&]<class N>() {
      if (c_.scene.tangential == sim::SlotChoice::On && tangential != N::tangential_name)
        v_.error(n["tangential"], "contact",
                 "tangential: " + tangential + " does not pair with model: " + N::name + "; use '" +
                     N::tangential_name + "', 'none' or 'auto'");
    });
    const std::string rolling = v_.string(n, d, "rolling", "contact", "auto");
    const std::string cohesion = v_.string(n, d, "cohesion", "contact", "auto");
    c_.scene.rolling = slot(rolling);
    c_.scene.cohesion = slot(cohesion);
    if (c_.scene.rolling == sim::SlotChoice::On) c_.scene.rolling_law = rolling;
    if (c_.scene.cohesion == sim::SlotChoice::On) c_.scene.cohesion_law = cohesion;
    const YAML::Node pairs = n["pairs"];
    if (!pairs) return;
    if (!pairs.IsSequence()) {
      v_.error(pairs, "contact.pairs", "expected a list of pair overrides");
      return;
    }
    const auto& pd = doc("contact.pairs");
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto ctx = idx("contact.pairs", i);
      const YAML::Node p = pairs[i];
      if (!v_.check_map(p, pd, ctx)) continue;
      sim::PairOverride o;
      const YAML::Node ms = p["materials"];
      if (ms && (!ms.IsSequence() || ms.size() != 2)) {
        v_.error(ms, ctx, "materials must be a list of two material names");
      } else if (ms) {
        for (int k = 0; k < 2; ++k) (k == 0 ? o.a : o.b) = material_by_name(ms[k], ctx);
      }
      o.restitution = v_.number(p, pd, "restitution", ctx, -1);
      o.friction = v_.number(p, pd, "friction", ctx, -1);
      o.rolling_friction = v_.number(p, pd, "rolling_friction", ctx, -1);
      o.cohesion = v_.number(p, pd, "cohesion_energy_density", ctx, -1);
      o.work_of_adhesion = v_.number(p, pd, "work_of_adhesion", ctx, -1);
      if (o.work_of_adhesion > 0 && adhesion_where_.empty()) adhesion_where_ = v_.where(p["work_of_adhesion"]);
      parse_law_maps(p, ctx, o.normal);
      if (p[c_.scene.normal.name]) check_law_values(o.normal.over(c_.scene.normal.values), p[c_.scene.normal.name], ctx);
      c_.scene.overrides.push_back(o);
    }
  }

  int material_by_name(const YAML::Node& n, const std::string& ctx) {
    if (!n.IsScalar()) {
      v_.error(n, ctx, "expected a material name");
      return 0;
    }
    auto it = material_index_.find(n.Scalar());
    if (it != material_index_.end()) return it->second;
    v_.error(n, ctx, "unknown material '" + n.Scalar() + "'");
    return 0;
  }

  sim::Region region(const YAML::Node& n, const std::string& ctx) {
    static const EffectDoc rd{"region", "region: {min: [..], max: [..]}", "a box",
                              {sim::key("min", sim::KeyType::Vec3, "lower corner").req().si("m"),
                               sim::key("max", sim::KeyType::Vec3, "upper corner").req().si("m")}};
    sim::Region r;
    if (!v_.check_map(n, rd, ctx)) return r;
    r.lo = v_.vec3(n, rd, "min", ctx);
    r.hi = v_.vec3(n, rd, "max", ctx);
    if (n["min"] && n["max"] && ((r.hi - r.lo).array() <= 0).any())
      v_.error(n["max"], ctx, "max must exceed min in every coordinate");
    return r;
  }

  void parse_radius(const YAML::Node& set, sim::ParticleSetConfig& p, const std::string& ctx) {
    const YAML::Node r = set["radius"];
    if (!r) return;
    const auto& d = doc("particles");
    if (r.IsScalar()) {
      p.size.radius = v_.number(set, d, "radius", ctx, 1);
      return;
    }
    const auto& dd = doc("particles.radius");
    const auto c2 = ctx + ".radius";
    if (!v_.check_map(r, dd, c2)) return;
    using K = sim::SizeDistribution::Kind;
    const std::string kind = v_.string(r, dd, "distribution", c2, "uniform");
    auto& s = p.size;
    auto need = [&](const char* k) {
      if (!r[k]) v_.error(r, c2, std::string("distribution '") + kind + "' needs key '" + k + "'");
    };
    if (kind == "uniform" || kind == "normal" || kind == "lognormal") {
      s.kind = kind == "uniform" ? K::Uniform : kind == "normal" ? K::Normal : K::LogNormal;
      need("min");
      need("max");
      s.min = v_.number(r, dd, "min", c2, 1);
      s.max = v_.number(r, dd, "max", c2, 1);
      if (s.max < s.min) v_.error(r["max"], c2, "max must be >= min");
      if (kind != "uniform") {
        need("mean");
        need("std");
        s.mean = v_.number(r, dd, "mean", c2, 1);
        s.stddev = v_.number(r, dd, "std", c2, 0);
      }
    } else if (kind == "discrete") {
      s.kind = K::Discrete;
      need("values");
      s.values = v_.numbers(r, dd, "values", c2);
      s.weights = r["weights"] ? v_.numbers(r, dd, "weights", c2) : std::vector<double>(s.values.size(), 1.0);
      if (s.values.empty()) v_.error(r, c2, "values must list at least one radius");
      if (s.weights.size() != s.values.size())
        v_.error(r["weights"] ? r["weights"] : r, c2, "weights must have as many entries as values");
      for (double x : s.values)
        if (!(x > 0)) v_.error(r["values"], c2, "every radius in values must be > 0");
      for (double w : s.weights)
        if (!(w >= 0)) v_.error(r["weights"], c2, "weights must be >= 0");
    }
  }

  void parse_placement(const YAML::Node& n, sim::ParticleSetConfig& p, const std::string& ctx0) {
    const auto ctx = ctx0 + ".placement";
    if (!check_type(n, ctx, "placement", {"random_fill", "lattice", "file"})) return;
    const YAML::Node t = n["type"];
    const auto& d = doc("placement." + t.Scalar());
    if (!v_.check_map(n, d, ctx)) return;
    auto& pl = p.placement;
    pl.seed = static_cast<std::uint64_t>(v_.integer(n, d, "seed", ctx, 1));
    if (t.Scalar() == "random_fill") {
      pl.kind = sim::Placement::Kind::RandomFill;
      if (n["region"]) pl.region = region(n["region"], ctx + ".region");
    } else if (t.Scalar() == "lattice") {
      pl.kind = sim::Placement::Kind::Lattice;
      if (n["region"]) pl.region = region(n["region"], ctx + ".region");
      pl.spacing = v_.number(n, d, "spacing", ctx, 0);
    } else {
      pl.kind = sim::Placement::Kind::File;
      const std::string path = v_.string(n, d, "path", ctx);
      if (!path.empty()) read_positions(n["path"], path, pl, ctx);
    }
  }

  void read_positions(const YAML::Node& at, const std::string& rel, sim::Placement& pl, const std::string& ctx) {
    namespace fs = std::filesystem;
    const fs::path path = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(c_.base_dir) / rel;
    std::ifstream in(path);
    if (!in) {
      v_.error(at, ctx, "cannot open positions file '" + path.string() + "'");
      return;
    }
    pl.positions_path = path.string();
    // Parsed in place (strtod on the line): a file of 10^7 grains reads in
    // seconds, and each position keeps only its line number for messages.
    std::string line;
    std::int64_t lineno = 0;
    int columns = -1;
    double vals[5];
    while (std::getline(in, line)) {
      ++lineno;
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      std::replace(line.begin(), line.end(), ',', ' ');
      int count = 0;
      bool bad = false;
      const char* p = line.c_str();
      while (true) {
        while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
        if (!*p) break;
        const char* tok = p;
        while (*p && *p != ' ' && *p != '\t' && *p != '\r') ++p;
        char* end = nullptr;
        const double x = std::strtod(tok, &end);
        if (end != p || !std::isfinite(x)) bad = true;
        if (count < 5) vals[count] = x;
        ++count;
      }
      if (count == 0 && !bad) continue;
      auto where = [&] { return path.string() + ":" + std::to_string(lineno); };
      if (bad || (count != 3 && count != 4)) {
        v_.error_at(where(), "expected 'x y z' or 'x y z r' with finite numbers, got '" + line + "'");
        continue;
      }
      if (columns < 0) columns = count;
      if (count != columns) {
        v_.error_at(where(), "every line must have the same number of columns (" + std::to_string(columns) + ")");
        continue;
      }
      if (count == 4 && !(vals[3] > 0)) {
        v_.error_at(where(), "radius must be > 0");
        continue;
      }
      pl.positions.emplace_back(vals[0], vals[1], vals[2]);
      if (count == 4) pl.radii.push_back(vals[3]);
      pl.position_line.push_back(lineno);
    }
    if (pl.positions.empty()) v_.error(at, ctx, "positions file '" + path.string() + "' holds no positions");
  }

  void parse_shape(const YAML::Node& n, sim::ParticleSetConfig& p, const std::string& ctx) {
    const auto& d = doc("particles.shape");
    if (!v_.check_map(n, d, ctx)) return;
    auto& sh = p.shape;
    const std::string type = v_.string(n, d, "type", ctx, "sphere");
    for (const char* k : {"file", "mesh", "grid", "mu"})
      if (n[k] && type != "clump") v_.error(n[k], ctx, std::string("'") + k + "' applies to type: clump only");
    if (type == "clump") {
      parse_clump(n, d, sh, ctx);
      parse_orientation(n, sh, ctx);
      return;
    }
    if (type != "ellipsoid") return;
    sh.kind = sim::ShapeConfig::Kind::Ellipsoid;
    if (n["aspect_ratio"] && n["semi_axes"]) {
      v_.error(n["semi_axes"], ctx, "give either aspect_ratio or semi_axes, not both");
    } else if (n["aspect_ratio"]) {
      const double a = v_.number(n, d, "aspect_ratio", ctx, 1);
      const Vec3 axes(std::cbrt(a * a), 1 / std::cbrt(a), 1 / std::cbrt(a));  // volume of the unit sphere
      sh.bounding_factor = axes.maxCoeff();
      sh.axes_rel = axes / sh.bounding_factor;
    } else if (n["semi_axes"]) {
      const Vec3 axes = v_.vec3(n, d, "semi_axes", ctx, Vec3(1, 1, 1));
      if ((axes.array() <= 0).any()) {
        v_.error(n["semi_axes"], ctx, "semi_axes must all be > 0");
      } else {
        sh.axes_rel = axes / axes.maxCoeff();
        if (sh.axes_rel.minCoeff() < 1e-3)
          v_.error(n["semi_axes"], ctx, "aspect ratios above 1000 are not supported (PW85 accuracy); valid: max/min <= 1000");
      }
    } else {
      v_.error(n, ctx, "an ellipsoid needs aspect_ratio or semi_axes");
    }
    parse_orientation(n, sh, ctx);
  }

  // A clump from a clump file or a mesh decomposed now (io/case/clump_shapes.hpp).
  void parse_clump(const YAML::Node& n, const EffectDoc& d, sim::ShapeConfig& sh, const std::string& ctx) {
    namespace fs = std::filesystem;
    sh.kind = sim::ShapeConfig::Kind::Clump;
    for (const char* k : {"aspect_ratio", "semi_axes"})
      if (n[k]) v_.error(n[k], ctx, std::string("'") + k + "' applies to type: ellipsoid only");
    if (n["file"] && n["mesh"]) {
      v_.error(n["mesh"], ctx, "give either file (a clump file) or mesh (decomposed at load time), not both");
      return;
    }
    if (!n["file"] && !n["mesh"]) {
      v_.error(n, ctx, "a clump needs file (a clump file from `grains clump`) or mesh (an .stl/.obj/.off file)");
      return;
    }
    if (n["file"] && (n["grid"] || n["mu"]))
      v_.error(n["grid"] ? n["grid"] : n["mu"], ctx, "grid and mu apply to mesh only (a clump file is decomposed already)");
    const char* key = n["file"] ? "file" : "mesh";
    const std::string rel = v_.string(n, d, key, ctx);
    if (rel.empty()) return;
    const fs::path path = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(c_.base_dir) / rel;
    const int grid = static_cast<int>(v_.integer(n, d, "grid", ctx, 32));
    const double mu = v_.number(n, d, "mu", ctx, 0.25);
    if (!v_.ok()) return;
    try {
      sh.clump = n["file"] ? clump_shape_from_file(path.string()) : clump_shape_from_mesh(path.string(), grid, mu);
    } catch (const std::exception& e) {
      v_.error(n[key], ctx, std::string("cannot make the clump shape: ") + e.what());
    }
  }

  void parse_orientation(const YAML::Node& n, sim::ShapeConfig& sh, const std::string& ctx) {
    const YAML::Node o = n["orientation"];
    if (!o) return;
    if (o.IsScalar() && o.Scalar() == "random") return;
    if (o.IsSequence() && o.size() == 4) {
      double q[4];
      for (int k = 0; k < 4; ++k)
        if (!v_.to_number(o[k], ctx, "orientation[" + std::to_string(k) + "]", q[k])) return;
      sim::Quat qq(q[0], q[1], q[2], q[3]);
      if (qq.norm() == 0) {
        v_.error(o, ctx, "orientation quaternion must not be zero");
        return;
      }
      sh.orientation = qq.normalized();
      sh.random_orientation = false;
      return;
    }
    v_.error(o, ctx, "orientation must be 'random' or a quaternion [w, x, y, z]");
  }

  // The `type` key that selects which keys a map may have: present, a
  // string, one of `kinds`; otherwise an error with a suggestion.
  bool check_type(const YAML::Node& n, const std::string& ctx, const std::string& what,
                  const std::vector<std::string>& kinds) {
    if (!n.IsMap()) {
      v_.error(n, ctx, "expected a map with a type (" + join_words(kinds) + ")");
      return false;
    }
    const YAML::Node t = n["type"];
    if (t && t.IsScalar() && std::find(kinds.begin(), kinds.end(), t.Scalar()) != kinds.end()) return true;
    const std::string got = t && t.IsScalar() ? t.Scalar() : "";
    const std::string guess = closest(got, kinds);
    v_.error(t ? t : n, ctx,
             (t ? what + " type '" + got + "' is not valid" : std::string("missing required key 'type'")) +
                 (guess.empty() ? "" : "; did you mean '" + guess + "'?") + " valid: " + join_words(kinds));
    return false;
  }

  static std::string join_words(const std::vector<std::string>& w) {
    std::string s;
    for (const auto& x : w) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  void parse_particles(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsSequence() || n.size() == 0) {
      v_.error(n, "particles", "expected a non-empty list of particle sets");
      return;
    }
    const auto& d = doc("particles");
    for (std::size_t i = 0; i < n.size(); ++i) {
      const auto ctx = idx("particles", i);
      const YAML::Node s = n[i];
      if (!v_.check_map(s, d, ctx)) continue;
      sim::ParticleSetConfig p;
      p.where = v_.where(s);
      p.name = v_.string(s, d, "name", ctx, "set" + std::to_string(i));
      p.material = material(s, d, ctx);
      parse_radius(s, p, ctx);
      p.count = v_.integer(s, d, "count", ctx, 0);
      p.velocity = v_.vec3(s, d, "velocity", ctx);
      p.frozen = v_.boolean(s, d, "frozen", ctx, false);
      if (s["shape"]) parse_shape(s["shape"], p, ctx + ".shape");
      if (p.frozen && p.shape.kind == sim::ShapeConfig::Kind::Clump)
        v_.error(s["frozen"], ctx + ".frozen", "frozen clumps are not supported (frozen sets are spheres or ellipsoids)");
      if (s["placement"]) parse_placement(s["placement"], p, ctx);
      if (p.placement.kind == sim::Placement::Kind::RandomFill && s["placement"] && !s["count"])
        v_.error(s, ctx, "random_fill needs 'count' (the number of particles to place)");
      c_.scene.sets.push_back(std::move(p));
    }
  }

  // insert[]: grains described as a particle set, plus when, where and how.
  void parse_insert(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsSequence() || n.size() == 0) {
      v_.error(n, "insert", "expected a non-empty list of insertions");
      return;
    }
    const auto& d = doc("insert");
    for (std::size_t i = 0; i < n.size(); ++i) {
      const auto ctx = idx("insert", i);
      const YAML::Node e = n[i];
      if (!v_.check_map(e, d, ctx)) continue;
      sim::InsertionConfig c;
      c.where = v_.where(e);
      auto& g = c.grains;
      g.where = c.where;
      g.name = v_.string(e, d, "name", ctx, "insert" + std::to_string(i));
      g.material = material(e, d, ctx);
      parse_radius(e, g, ctx);
      g.count = v_.integer(e, d, "count", ctx, 1);
      g.velocity = v_.vec3(e, d, "velocity", ctx);
      if (e["shape"]) parse_shape(e["shape"], g, ctx + ".shape");
      if (e["region"]) c.region = region(e["region"], ctx + ".region");
      const std::string method = v_.string(e, d, "method", ctx, "fft");
      c.method = method == "random" ? sim::InsertionConfig::Method::Random : sim::InsertionConfig::Method::Fft;
      c.at = v_.number(e, d, "at", ctx, 0);
      c.every = v_.number(e, d, "every", ctx, 0);
      c.until = v_.number(e, d, "until", ctx, 0);
      if (e["until"] && c.until < c.at) v_.error(e["until"], ctx, "until must not be before at");
      c.times = v_.integer(e, d, "times", ctx, 0);
      if (e["times"] && !e["every"])
        v_.error(e["times"], ctx, "'times' caps repeated insertions and applies with every only (without every the "
                                  "grains are inserted once)");
      c.orientations = static_cast<int>(v_.integer(e, d, "orientations", ctx, 8));
      c.spacing = v_.number(e, d, "spacing", ctx, 0);
      c.margin = v_.number(e, d, "margin", ctx, 0.25);
      c.mode_factor = v_.number(e, d, "mode_factor", ctx, 1);
      c.attempts = v_.integer(e, d, "attempts", ctx, 100000);
      c.budget = v_.number(e, d, "budget", ctx, 0);
      c.seed = static_cast<std::uint64_t>(v_.integer(e, d, "seed", ctx, 1));
      // (Not when the method itself is misspelt: that error says enough.)
      const YAML::Node m = e["method"];
      const bool known = !m || (m.IsScalar() && (m.Scalar() == "fft" || m.Scalar() == "random"));
      const bool fft = c.method == sim::InsertionConfig::Method::Fft;
      for (const char* k : {"orientations", "spacing", "margin", "mode_factor"})
        if (known && e[k] && !fft) v_.error(e[k], ctx, std::string("'") + k + "' applies to method: fft only");
      if (known && e["attempts"] && fft) v_.error(e["attempts"], ctx, "'attempts' applies to method: random only");
      c_.scene.insertions.push_back(std::move(c));
    }
  }

  // A wall kind's own keys, read against its documentation (sim/walls/wall_kind.hpp).
  class WallKeys final : public sim::KeyReader {
   public:
    WallKeys(Validator& v, const YAML::Node& map, const EffectDoc& d, std::string ctx, std::string base_dir,
             std::vector<std::string>& warnings)
        : v_(v), map_(map), d_(d), ctx_(std::move(ctx)), base_dir_(std::move(base_dir)), warnings_(warnings) {}
    bool has(const std::string& k) const override { return static_cast<bool>(map_[k]); }
    double number(const std::string& k, double fallback) override {
      const double def = d_.find(k) ? d_.find(k)->default_number : fallback;
      return v_.number(map_, d_, k, ctx_, def == def ? def : fallback);
    }
    Vec3 vec3(const std::string& k, const Vec3& fallback) override { return v_.vec3(map_, d_, k, ctx_, fallback); }
    bool boolean(const std::string& k, bool fallback) override { return v_.boolean(map_, d_, k, ctx_, fallback); }
    std::string string(const std::string& k, const std::string& fallback) override {
      return v_.string(map_, d_, k, ctx_, fallback);
    }
    std::shared_ptr<const mesh::TriangleMesh> surface_mesh(const std::string& k) override {
      const std::string rel = v_.string(map_, d_, k, ctx_, "");
      if (rel.empty()) return nullptr;
      namespace fs = std::filesystem;
      const fs::path path = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(base_dir_) / rel;
      try {
        mesh::ValidationOptions opt;
        opt.wall_surface = true;
        auto m = std::make_shared<mesh::TriangleMesh>(mesh::load_mesh(path.string(), opt));
        for (const auto& w : m->warnings) warning(k, w);
        return m;
      } catch (const std::exception& e) {
        error(k, std::string("cannot use the mesh: ") + e.what());
        return nullptr;
      }
    }
    void warning(const std::string& k, const std::string& msg) override {
      warnings_.push_back(v_.where(map_[k] ? map_[k] : map_) + ": " + ctx_ + ": warning: " + msg);
    }
    void error(const std::string& k, const std::string& msg) override {
      v_.error(map_[k] ? map_[k] : map_, ctx_, msg);
    }

   private:
    Validator& v_;
    const YAML::Node& map_;
    const EffectDoc& d_;
    std::string ctx_;
    std::string base_dir_;
    std::vector<std::string>& warnings_;
  };

  void parse_walls(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsSequence()) {
      v_.error(n, "walls", "expected a list of walls");
      return;
    }
    std::vector<std::string> kinds;
    sim::for_each_type(sim::WallKinds{}, [&]<class K>() { kinds.push_back(K::kind); });
    for (std::size_t i = 0; i < n.size(); ++i) {
      const auto ctx = idx("walls", i);
      const YAML::Node w = n[i];
      if (!check_type(w, ctx, "wall", kinds)) continue;
      const YAML::Node t = w["type"];
      const auto& d = doc("walls." + t.Scalar());
      if (!v_.check_map(w, d, ctx)) continue;
      sim::for_each_type(sim::WallKinds{}, [&]<class K>() {
        if (t.Scalar() != K::kind) return;
        WallKeys keys(v_, w, d, ctx, c_.base_dir, c_.scene.warnings);
        K wall = K::from_keys(keys);
        wall.name = v_.string(w, d, "name", ctx, t.Scalar() + std::to_string(i));
        wall.material = material(w, d, ctx);
        wall.velocity = v_.vec3(w, d, "velocity", ctx);
        wall.where = v_.where(w);
        if constexpr (K::controllable)
          if (const YAML::Node cn = w["control"]) parse_control(cn, w, ctx + ".control", wall);
        c_.scene.walls.add(wall);
      });
    }
  }

  // walls[].control (sim/walls/wall_control.hpp): one of stress, force, strain_rate.
  template <class K>
  void parse_control(const YAML::Node& n, const YAML::Node& w, const std::string& ctx, K& wall) {
    const auto& d = doc("walls.control");
    if (!v_.check_map(n, d, ctx)) return;
    sim::WallControl& c = wall.control;
    c.where = v_.where(n);
    int given = 0;
    for (const char* k : {"stress", "force", "strain_rate"}) given += n[k] ? 1 : 0;
    if (given != 1) {
      v_.error(n, ctx, "give exactly one of stress, force or strain_rate (" + std::to_string(given) + " given)");
      return;
    }
    if (w["velocity"])
      v_.error(w["velocity"], ctx, "a controlled wall's velocity is set by its control; remove velocity");
    using M = sim::WallControl::Mode;
    c.mode = n["stress"] ? M::Stress : n["force"] ? M::Force : M::StrainRate;
    const char* target_key = n["stress"] ? "stress" : n["force"] ? "force" : "strain_rate";
    c.target = v_.number(n, d, target_key, ctx, 0);
    if (c.mode != M::StrainRate && !(c.target > 0))
      v_.error(n[target_key], ctx,
               std::string(target_key) + " must be compressive, > 0 (the grains push on the wall; it cannot pull "
               "them): got " + n[target_key].Scalar());
    if (c.mode == M::StrainRate && c.target == 0)
      v_.error(n[target_key], ctx, "strain_rate must not be 0 (a wall at rest needs no control)");
    c.area = v_.number(n, d, "area", ctx, 0);
    if (n["area"] && c.mode != M::Stress) v_.error(n["area"], ctx, "area goes with stress");
    c.max_speed = v_.number(n, d, "max_speed", ctx, 0);
    if (c.mode != M::StrainRate && !n["max_speed"])
      v_.error(n, ctx, "a servo needs max_speed, the fastest the wall may move (e.g. a few percent of a grain "
                       "diameter per the time a sound wave crosses the sample)");
    if (c.mode == M::StrainRate && n["max_speed"])
      v_.error(n["max_speed"], ctx, "max_speed goes with stress or force (a strain rate sets the speed)");
    c.gain = v_.number(n, d, "gain", ctx, 0.5);
    if (n["gain"] && c.mode == M::StrainRate) v_.error(n["gain"], ctx, "gain goes with stress or force");
    if constexpr (requires { wall.normal; }) {
      c.direction = wall.normal;
      if (n["direction"]) v_.error(n["direction"], ctx, "a plane moves along its normal; remove direction");
    } else {
      if (!n["direction"]) v_.error(n, ctx, "give direction, the direction the wall moves towards the grains");
      const sim::Vec3 dir = v_.vec3(n, d, "direction", ctx, sim::Vec3(0, 0, 1));
      if (n["direction"] && dir.norm() == 0) v_.error(n["direction"], ctx, "direction must not be the zero vector");
      if (dir.norm() > 0) c.direction = dir.normalized();
      if (c.mode == M::StrainRate)
        v_.error(n["strain_rate"], ctx, "strain_rate moves plane walls (it needs the facing plane); give a mesh a "
                                        "velocity, or a servo");
    }
  }

  void parse_time(const YAML::Node& n) {
    if (!n) return;
    const auto& d = doc("time");
    if (!v_.check_map(n, d, "time")) return;
    auto& sc = c_.scene;
    sc.end_time = v_.number(n, d, "end", "time", 1);
    const std::string integrator = v_.string(n, d, "integrator", "time", "verlet");
    sc.integrator = integrator == "arkode" ? sim::Integrator::Arkode : sim::Integrator::Verlet;
    sc.integrator_where = v_.where(n["integrator"] ? n["integrator"] : n);
    // (Not when the integrator itself is misspelt: that error says enough.)
    const bool verlet = !n["integrator"] || (n["integrator"].IsScalar() && n["integrator"].Scalar() == "verlet");
    for (const char* k : {"rtol", "atol", "order"})
      if (n[k] && verlet)
        v_.error(n[k], "time", std::string(k) + " applies to integrator: arkode; this case integrates with verlet (fixed step dt)");
    sc.arkode.rtol = v_.number(n, d, "rtol", "time", sc.arkode.rtol);
    sc.arkode.atol = v_.number(n, d, "atol", "time", sc.arkode.atol);
    sc.arkode.order = static_cast<int>(v_.integer(n, d, "order", "time", sc.arkode.order));
    if (n["order"] && sc.arkode.order == 7) {
      v_.error(n["order"], "time", "order = 7 has no ARKODE explicit table; valid: 2, 3, 4, 5, 6, 8");
      sc.arkode.order = 4;
    }
    if (n["dt"] && n["dt_rayleigh"]) {
      v_.error(n["dt_rayleigh"], "time", "give either dt or dt_rayleigh, not both");
    } else if (!n["dt"] && !n["dt_rayleigh"]) {
      v_.error(n, "time", "missing the time step: give dt (seconds) or dt_rayleigh (fraction of the Rayleigh time, e.g. 0.2)");
    }
    sc.dt = v_.number(n, d, "dt", "time", 0);
    sc.dt_rayleigh = v_.number(n, d, "dt_rayleigh", "time", 0);
    sc.dt_where = v_.where(n["dt"] ? n["dt"] : n["dt_rayleigh"] ? n["dt_rayleigh"] : n);
  }

  void parse_neighbor(const YAML::Node& n) {
    if (!n) return;
    const auto& d = doc("neighbor");
    if (!v_.check_map(n, d, "neighbor")) return;
    c_.scene.skin = v_.number(n, d, "skin", "neighbor", 0.1);
    c_.scene.sort_particles = v_.boolean(n, d, "sort", "neighbor", true);
    c_.scene.skin_per_grain = v_.boolean(n, d, "skin_per_grain", "neighbor", false);
    c_.scene.overlap_tolerance = v_.number(n, d, "overlap_tolerance", "neighbor", 0.01);
  }

  void parse_growth(const YAML::Node& n) {
    if (!n) return;
    const auto& d = doc("radius_growth");
    if (!v_.check_map(n, d, "radius_growth")) return;
    auto& g = c_.scene.growth;
    g.enabled = true;
    const YAML::Node ph = n["phases"];
    if (ph && (n["rate"] || n["target_overlap"]))
      v_.error(ph, "radius_growth", "give either rate and target_overlap, or phases, not both");
    if (!ph && (!n["rate"] || !n["target_overlap"]))
      v_.error(n, "radius_growth", "missing rate and target_overlap (or a schedule: phases)");
    g.rate = v_.number(n, d, "rate", "radius_growth", 1);
    g.target_overlap = v_.number(n, d, "target_overlap", "radius_growth", 1e-4);
    if (ph) {
      if (!ph.IsSequence() || ph.size() == 0) {
        v_.error(ph, "radius_growth.phases", "expected a non-empty list of phases {rate, target_overlap, until}");
      } else {
        const auto& pd = doc("radius_growth.phases");
        for (std::size_t i = 0; i < ph.size(); ++i) {
          const auto ctx = idx("radius_growth.phases", i);
          if (!v_.check_map(ph[i], pd, ctx)) continue;
          sim::GrowthPhase q;
          q.rate = v_.number(ph[i], pd, "rate", ctx, 0);
          q.target_overlap = v_.number(ph[i], pd, "target_overlap", ctx, 1e-4);
          q.until = v_.number(ph[i], pd, "until", ctx, 0);
          if (!g.phases.empty() && q.until <= g.phases.back().until)
            v_.error(ph[i]["until"], ctx, "phases must be in time order (until after the previous phase's)");
          g.phases.push_back(q);
        }
        if (!g.phases.empty()) {
          g.rate = g.phases.front().rate;
          g.target_overlap = g.phases.front().target_overlap;
        }
      }
    }
    g.every_steps = v_.integer(n, d, "every_steps", "radius_growth", 10);
    g.max_scale = v_.number(n, d, "max_scale", "radius_growth", 2);
    c_.scene.growth_where = v_.where(n);
  }

  void parse_output(const YAML::Node& n) {
    if (!n) return;
    const auto& d = doc("output");
    if (!v_.check_map(n, d, "output")) return;
    auto& o = c_.output;
    if (n["every"] && n["every_steps"]) v_.error(n["every_steps"], "output", "give either every or every_steps, not both");
    o.every = v_.number(n, d, "every", "output", 0);
    o.every_steps = v_.integer(n, d, "every_steps", "output", 0);
    o.vtk = v_.boolean(n, d, "vtk", "output", true);
    o.progress = v_.boolean(n, d, "progress", "output", true);
    o.progress_interval = v_.number(n, d, "progress_interval", "output", 2.0);
    if (const YAML::Node sf = n["solid_fraction"]) {
      const auto& sd = doc("output.solid_fraction");
      const std::string ctx = "output.solid_fraction";
      if (v_.check_map(sf, sd, ctx)) {
        auto& c = o.solid_fraction;
        c.enabled = true;
        c.spacing = v_.number(sf, sd, "spacing", ctx, 1);
        c.smoothing = v_.number(sf, sd, "smoothing", ctx, -1);
        c.tolerance = v_.number(sf, sd, "tolerance", ctx, 1e-4);
        if (sf["every"] && sf["every_steps"]) v_.error(sf["every_steps"], ctx, "give either every or every_steps, not both");
        c.every = v_.number(sf, sd, "every", ctx, 0);
        c.every_steps = v_.integer(sf, sd, "every_steps", ctx, 0);
      }
    }
    if (const YAML::Node m = n["wall_loads"]) {
      const auto& md = doc("output.wall_loads");
      const std::string ctx = "output.wall_loads";
      if (v_.check_map(m, md, ctx)) {
        auto& c = o.wall_loads;
        c.enabled = true;
        if (m["every"] && m["every_steps"]) v_.error(m["every_steps"], ctx, "give either every or every_steps, not both");
        c.every = v_.number(m, md, "every", ctx, 0);
        c.every_steps = v_.integer(m, md, "every_steps", ctx, 0);
        c.average_after = v_.number(m, md, "average_after", ctx, 0);
      }
    }
    if (const YAML::Node m = n["stress"]) {
      const auto& md = doc("output.stress");
      const std::string ctx = "output.stress";
      if (v_.check_map(m, md, ctx)) {
        auto& c = o.stress;
        c.enabled = true;
        c.where = v_.where(m);
        if (m["every"] && m["every_steps"]) v_.error(m["every_steps"], ctx, "give either every or every_steps, not both");
        c.every = v_.number(m, md, "every", ctx, 0);
        c.every_steps = v_.integer(m, md, "every_steps", ctx, 0);
        c.average_after = v_.number(m, md, "average_after", ctx, 0);
        if (const YAML::Node r = m["region"]) {
          const sim::Region reg = region(r, ctx + ".region");
          c.region_given = true;
          c.lo = reg.lo, c.hi = reg.hi;
        }
        if (static_cast<bool>(m["profile_axis"]) != static_cast<bool>(m["bins"]))
          v_.error(m, ctx, "a profile needs both profile_axis and bins");
        const std::string axis = v_.string(m, md, "profile_axis", ctx, "");
        c.axis = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
        c.bins = c.axis >= 0 ? static_cast<int>(v_.integer(m, md, "bins", ctx, 0)) : 0;
      }
    }
    if (const YAML::Node m = n["mass"]) {
      const auto& md = doc("output.mass");
      const std::string ctx = "output.mass";
      if (v_.check_map(m, md, ctx)) {
        auto& c = o.mass;
        c.enabled = true;
        if (m["every"] && m["every_steps"]) v_.error(m["every_steps"], ctx, "give either every or every_steps, not both");
        c.every = v_.number(m, md, "every", ctx, 0);
        c.every_steps = v_.integer(m, md, "every_steps", ctx, 0);
        if (static_cast<bool>(m["point"]) != static_cast<bool>(m["normal"])) {
          v_.error(m, ctx, "give both point and normal of the counting plane, or neither");
        } else if (m["point"]) {
          c.has_plane = true;
          c.point = v_.vec3(m, md, "point", ctx);
          c.normal = v_.vec3(m, md, "normal", ctx, Vec3(0, 0, 1));
          if (c.normal.norm() == 0) {
            v_.error(m["normal"], ctx, "normal must not be the zero vector");
            c.normal = Vec3(0, 0, 1);
          }
          c.normal.normalize();
        }
      }
    }
  }

  void parse_checkpoint(const YAML::Node& n) {
    if (!n) return;
    const auto& d = doc("checkpoint");
    if (!v_.check_map(n, d, "checkpoint")) return;
    auto& k = c_.checkpoint;
    if (n["every"] && n["every_steps"])
      v_.error(n["every_steps"], "checkpoint", "give either every or every_steps, not both");
    k.every = v_.number(n, d, "every", "checkpoint", 0);
    k.every_steps = v_.integer(n, d, "every_steps", "checkpoint", 0);
    k.keep = static_cast<int>(v_.integer(n, d, "keep", "checkpoint", 3));
  }

  Case& c_;
  Validator& v_;
  std::map<std::string, int> material_index_;
  std::string adhesion_where_;  // the first positive surface_energy or work_of_adhesion
};

// Applies "a.b.0.c=value" to the tree; records where the value came from.
void apply_override(YAML::Node& root, const std::string& text, Validator& v) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    v.error_at("--set " + text, "expected key.path=value, e.g. --set time.end=0.5");
    return;
  }
  const std::string path = text.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(text.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    v.error_at("--set " + text, std::string("the value is not valid YAML: ") + e.msg);
    return;
  }
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  YAML::Node cur = root;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    const bool last = i + 1 == parts.size();
    if (cur.IsSequence()) {
      char* end = nullptr;
      const long k = std::strtol(p.c_str(), &end, 10);
      if (end != p.c_str() + p.size() || k < 0 || static_cast<std::size_t>(k) >= cur.size()) {
        v.error_at("--set " + text, "'" + p + "' is not an index of the list (it has " + std::to_string(cur.size()) +
                                        " entries, 0.." + std::to_string(cur.size() ? cur.size() - 1 : 0) + ")");
        return;
      }
      if (last) {
        cur[k] = value;
        v.mark_override(cur[k], text);
        return;
      }
      cur.reset(cur[k]);
    } else {
      if (!cur.IsMap() && !cur.IsNull()) {
        v.error_at("--set " + text, "cannot descend into '" + p + "': the parent is not a map");
        return;
      }
      if (last) {
        cur[p] = value;
        YAML::Node set = cur[p];
        v.mark_override(set, text);
        return;
      }
      YAML::Node next = cur[p];
      if (!next) {  // a section the case does not have yet: create it
        cur[p] = YAML::Node(YAML::NodeType::Map);
        next = cur[p];
      }
      cur.reset(next);
    }
  }
}

}  // namespace

Case parse_case(const std::string& text, const std::string& name, const std::vector<std::string>& overrides,
                const std::string& base_dir) {
  const auto started = std::chrono::steady_clock::now();
  register_io_docs();
  Case c;
  c.path = name;
  c.base_dir = base_dir;
  c.text = text;
  Validator v(name);
  try {
    c.root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw CaseError({name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                     ": YAML syntax error: " + e.msg});
  }
  if (c.root.IsNull()) throw CaseError({name + ": the case file is empty; see `grains docs case` for the keys"});
  for (const auto& o : overrides) apply_override(c.root, o, v);
  v.throw_if_errors();
  CaseParser(c, v).parse();
  v.throw_if_errors();
  c.read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return c;
}

Case load_case(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError({path + ": cannot open the case file"});
  std::stringstream ss;
  ss << in.rdbuf();
  const auto dir = std::filesystem::path(path).parent_path();
  return parse_case(ss.str(), path, overrides, dir.empty() ? "." : dir.string());
}

}  // namespace grains::io
