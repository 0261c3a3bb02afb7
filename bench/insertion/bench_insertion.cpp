// Places as many grains as fit into a region of a dense bed, with the FFT
// method and with random trials, each given the same wall-clock budget, and
// prints one CSV row per (method, budget):
//
//   bench_insertion CASE CHECKPOINT [options]
//     --region x0 y0 z0 x1 y1 z1   insertion region (m); default the domain
//     --radius r                   bounding radius of the inserted grains (m)
//     --shape sphere|ellipsoid     --aspect a (prolate ellipsoid a : 1 : 1)
//     --budgets b1,b2,...          seconds (default 0.5,1,2,4,8)
//     --spacing h  --mode-factor m  --margin f  --orientations n   (fft)
//     --seed s
//
// The bed is the case's scene restored from the checkpoint (e.g. the end of
// cases/jam_frictionless). Every placed grain is checked again afterwards
// by brute force against the bed and the other placed grains (spheres:
// distances with periodic images; ellipsoids: PW85), and the row says how
// many failed (must be 0).
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

#include "contact/ellipsoid/pw85.hpp"
#include "io/case/case.hpp"
#include "io/checkpoint/checkpoint.hpp"
#include "io/run/simulation.hpp"
#include "sim/insert/grain_geometry.hpp"
#include "sim/insert/insertion_stage.hpp"

using namespace grains;
using sim::Vec3;

namespace {

std::vector<double> parse_list(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string t; std::getline(ss, t, ',');) v.push_back(std::stod(t));
  return v;
}

// Brute-force recount of overlaps of the placed grains (tolerance-free).
int count_overlaps(const sim::InsertionConfig& c, const sim::insert::SceneGrains& bed,
                   const std::vector<sim::insert::NewGrain>& out, const sim::Domain& d) {
  struct P {
    Vec3 x;
    double b;
    bool ell;
    contact::SymMat3 q;
    long g;
  };
  std::vector<P> parts;
  for (std::size_t i = 0; i < bed.sphere_r.size(); ++i)
    parts.push_back({bed.sphere_x[i], bed.sphere_r[i], false, {}, -1});
  for (std::size_t i = 0; i < bed.ell_x.size(); ++i)
    parts.push_back({bed.ell_x[i], bed.ell_axes[i].maxCoeff(), true,
                     contact::quadratic_form(bed.ell_axes[i], bed.ell_q[i]), -1});
  const std::size_t n0 = parts.size();
  for (std::size_t k = 0; k < out.size(); ++k) {
    const auto g = sim::insert::grain_parts(c.grains.shape, out[k].r, out[k].x, out[k].o);
    if (g.ellipsoid) parts.push_back({g.ell_centre, g.ell_bound, true, g.form, static_cast<long>(k)});
    for (std::size_t b = 0; b < g.radii.size(); ++b)
      parts.push_back({g.centres[b], g.radii[b], false, {}, static_cast<long>(k)});
  }
  auto form = [](const P& p) { return p.ell ? p.q : contact::SymMat3{p.b * p.b, 0, 0, p.b * p.b, 0, p.b * p.b}; };
  int bad = 0;
  for (std::size_t i = n0; i < parts.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      if (parts[i].g == parts[j].g) continue;
      Vec3 r = parts[j].x - parts[i].x;
      for (int a = 0; a < 3; ++a)
        if (d.periodic[a]) r[a] -= (d.hi[a] - d.lo[a]) * std::round(r[a] / (d.hi[a] - d.lo[a]));
      if (r.norm() >= parts[i].b + parts[j].b) continue;
      if (!parts[i].ell && !parts[j].ell) {
        ++bad;
        continue;
      }
      if (contact::pw85_contact(r, form(parts[i]), form(parts[j])).mu2 < 1) ++bad;
    }
  return bad;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: bench_insertion CASE CHECKPOINT [--region x0 y0 z0 x1 y1 z1] [--radius r] "
                 "[--shape sphere|ellipsoid] [--aspect a] [--budgets b1,b2,..] [--spacing h] [--mode-factor m] "
                 "[--margin f] [--orientations n] [--seed s]\n";
    return 2;
  }
  auto simu = io::make_simulation(io::load_case(argv[1]));
  io::read_checkpoint(argv[2], simu.scene);
  const auto& dom = simu.scene.domain;
  sim::InsertionConfig c;
  c.region.lo = dom.lo;
  c.region.hi = dom.hi;
  c.grains.name = "bench";
  c.grains.size.radius = 1e-4;
  c.grains.count = 1000000;  // as many as fit in the budget
  c.attempts = std::numeric_limits<std::int64_t>::max();
  std::vector<double> budgets{0.5, 1, 2, 4, 8};
  std::string shape = "sphere";
  double aspect = 2;
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&] { return std::string(argv[++i]); };
    if (a == "--region") {
      for (int d = 0; d < 3; ++d) c.region.lo[d] = std::stod(next());
      for (int d = 0; d < 3; ++d) c.region.hi[d] = std::stod(next());
    } else if (a == "--radius") c.grains.size.radius = std::stod(next());
    else if (a == "--shape") shape = next();
    else if (a == "--aspect") aspect = std::stod(next());
    else if (a == "--budgets") budgets = parse_list(next());
    else if (a == "--spacing") c.spacing = std::stod(next());
    else if (a == "--mode-factor") c.mode_factor = std::stod(next());
    else if (a == "--margin") c.margin = std::stod(next());
    else if (a == "--orientations") c.orientations = std::stoi(next());
    else if (a == "--seed") c.seed = std::stoull(next());
    else {
      std::cerr << "unknown option " << a << "\n";
      return 2;
    }
  }
  if (shape == "ellipsoid") {
    c.grains.shape.kind = sim::ShapeConfig::Kind::Ellipsoid;
    c.grains.shape.axes_rel = Vec3(1, 1 / aspect, 1 / aspect);
  }
  const auto bed = sim::gather_scene_grains(simu.scene);
  double vs = 0, rsum = 0;
  for (double r : bed.sphere_r) vs += 4.0 / 3.0 * M_PI * r * r * r, rsum += r;
  std::cerr << "bed: " << bed.sphere_r.size() << " spheres (mean radius "
            << rsum / std::max<std::size_t>(1, bed.sphere_r.size()) << " m), " << bed.ell_x.size()
            << " ellipsoids; solid fraction of the domain (spheres) " << vs / (dom.hi - dom.lo).prod() << "\n";
  std::cout << "shape,method,budget_s,placed,trials,fields,candidates,field_s,total_s,overlaps\n";
  for (double b : budgets)
    for (auto m : {sim::InsertionConfig::Method::Fft, sim::InsertionConfig::Method::Random}) {
      c.method = m;
      c.budget = b;
      sim::insert::InsertStats st;
      const auto out = sim::insert::insert_grains(c, bed, dom, simu.scene.walls, c.seed, 1, &st);
      std::cout << shape << "," << (m == sim::InsertionConfig::Method::Fft ? "fft" : "random") << "," << b << ","
                << st.placed << "," << st.trials << "," << st.fields << "," << st.candidates << ","
                << st.field_seconds << "," << st.seconds << "," << count_overlaps(c, bed, out, dom) << std::endl;
    }
}
