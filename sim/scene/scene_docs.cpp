// Case-file keys of the scene sections (domain, particles, time, neighbour
// lists, gravity) and the registry of all sim effects.
#include <limits>

#include "sim/keys/effect_doc.hpp"

namespace grains::sim {

std::vector<EffectDoc> law_docs();
std::vector<EffectDoc> wall_docs();
std::vector<EffectDoc> insertion_docs();

namespace {

std::vector<EffectDoc> scene_docs() {
  const double inf = std::numeric_limits<double>::infinity();
  using K = KeyType;
  std::vector<EffectDoc> d;
  d.push_back({"case", "(top level)", "A grains case file. All values in SI units.",
               {key("title", K::String, "free text"), key("description", K::String, "free text"),
                key("domain", K::Map, "the simulation box").req(),
                key("gravity", K::Vec3, "gravitational acceleration; absent or zero: no gravity stage").si("m/s^2"),
                key("materials", K::List, "materials (see materials)").req(),
                key("contact", K::Map, "contact law slots and pair overrides (see contact)"),
                key("particles", K::List, "particle sets (see particles); may be left out when insert[] adds all the grains"),
                key("walls", K::List, "walls (see walls.<type>: one section per wall kind)"),
                key("time", K::Map, "time stepping (see time)").req(),
                key("neighbor", K::Map, "neighbour lists (see neighbor)"),
                key("parallel", K::Map, "threads and MPI ranks (see parallel)"),
                key("output", K::Map, "output (see output)"),
                key("checkpoint", K::Map, "HDF5 checkpoints for restart (see checkpoint)"),
                key("radius_growth", K::Map, "isotropic compression by growing radii (see radius_growth)"),
                key("insert", K::List, "grains inserted during the run where they overlap nothing (see insert)")}});
  d.push_back({"radius_growth", "radius_growth: {...}",
               "Isotropic compression by growing radii (a jamming protocol): each step every radius is multiplied "
               "by exp(g dt), g = rate * clamp(1 - o/target_overlap, -1, 1), where the overlap per particle o is the "
               "sum over touching pairs of delta/(r_i + r_j) divided by the number of particles (about Z/2 times the "
               "mean relative overlap of a contact: zero while the packing is loose). The packing grows at `rate` "
               "until contacts carry load and settles at o = target_overlap (radii shrink back if compressed "
               "beyond it). Masses keep the density (m ~ r^3), so the time step of the initial radii stays safe. "
               "Spheres only.",
               {key("rate", K::Number, "largest relative growth rate d ln r/dt (or give phases)").si("1/s").in(0, inf, true),
                key("target_overlap", K::Number, "overlap per particle o at which growth stops, e.g. 2e-3 (or give phases)")
                    .in(0, 0.1, true),
                key("phases", K::List,
                    "a schedule instead of rate and target_overlap: [{rate, target_overlap, until}, ...] in time "
                    "order (see radius_growth.phases); after the last phase the radii stay fixed"),
                key("every_steps", K::Integer, "steps between measurements of o").def("10").in(1, 1e9),
                key("max_scale", K::Number,
                    "radii grow to at most this times their initial size (sizes the ghost cut-off of periodic runs)")
                    .def("2").in(1, 10, true)}});
  d.push_back({"radius_growth.phases", "radius_growth: {phases: [{...}, ...]}",
               "One phase of a compression schedule, applied until the simulated time `until`; rate 0 holds the "
               "radii fixed while the packing relaxes. E.g. fast growth to a dense fluid, slow growth until it jams, "
               "decompression to a lower target, relaxation (cases/jam_frictionless).",
               {key("rate", K::Number, "largest relative growth rate in this phase; 0: radii fixed")
                    .req().si("1/s").in(0, inf),
                key("target_overlap", K::Number, "overlap per particle the servo aims at").req().in(0, 0.1, true),
                key("until", K::Number, "end of the phase (simulated time)").req().si("s").in(0, inf, true)}});
  d.push_back({"domain", "domain: {...}",
               "The box particles live in; a particle that leaves it through a non-periodic face is removed and "
               "counted in the summary. Through a periodic face it comes back at the opposite one, and contacts "
               "act across periodic faces (ghost images; the box must be at least twice the largest diameter "
               "plus skin along a periodic axis).",
               {key("min", K::Vec3, "lower corner").req().si("m"), key("max", K::Vec3, "upper corner").req().si("m"),
                key("periodic", K::Bool3, "periodic axes: true/false for all, or [x, y, z]").def("false"),
                key("shear", K::Map, "Lees-Edwards boundaries for steady simple shear (see domain.shear)")}});
  d.push_back({"domain.shear", "domain: {..., shear: {rate: 10, flow: x, gradient: y}}",
               "Lees-Edwards boundaries: steady simple shear at `rate` with no walls. The flow and gradient axes "
               "must be periodic; the image of the cell across the gradient's upper face is displaced along the "
               "flow by rate L_g t and moves at rate L_g relative to it, so a grain leaving through that face comes "
               "back through the lower one displaced and slowed by rate L_g (and the other way round); contacts act "
               "across it with that relative velocity. The mean flow is u = rate (y - y_centre) along the flow. With "
               "initial_profile the grains start on it. With pressure the cell's height along the gradient follows a "
               "servo holding the normal stress across it (contact + kinetic, the whole cell) at that value (da Cruz "
               "et al. 2005): (dL/dt)/L = gain |rate| (sigma - pressure)/pressure, clamped to max_dilation, the grains' "
               "coordinates along the gradient scaled with it. Under MPI the ranks split the gradient and the third "
               "axis, never the flow. Verlet only; not with clumps.",
               {key("rate", K::Number, "shear rate du_flow/dx_gradient (either sign)").req().si("1/s"),
                key("flow", K::String, "the axis of the mean flow").req().one_of({"x", "y", "z"}),
                key("gradient", K::String, "the axis the flow varies along").req().one_of({"x", "y", "z"}),
                key("initial_profile", K::Bool, "add the mean flow rate (y - y_centre) to the grains' velocities at the start")
                    .def_bool(true),
                key("pressure", K::Number, "normal stress the cell holds across the gradient, > 0; absent: the "
                                           "volume is fixed").si("Pa"),
                key("gain", K::Number, "the servo's relative dilation rate per relative pressure error, in units of "
                                       "|rate|").def(0.1).in(0, 10, true),
                key("max_dilation", K::Number, "the fastest relative change of the cell's height; default |rate|")
                    .si("1/s").in(0, inf, true)}});
  d.push_back({"force.gravity", "gravity: [gx, gy, gz]", "Uniform gravity, F = m g, applied where forces are cleared each step; absent or zero costs nothing.",
               {key("gravity", K::Vec3, "acceleration").si("m/s^2")}});
  d.push_back({"particles", "particles: [ {...}, ... ]", "A set of particles: spheres, ellipsoids or rigid clumps (see particles.shape).",
               {key("name", K::String, "label").def("set<k>"),
                key("material", K::String, "material name").req(),
                key("radius", K::Number,
                    "a radius (number) or a size distribution (map, see particles.radius)")
                    .req().si("m").in(0, inf, true),
                key("count", K::Integer, "number of particles (lattice: optional, fills the region)").in(1, 1e12),
                key("placement", K::Map, "where the particles start (see placement.*)").req(),
                key("shape", K::Map, "particle shape (see particles.shape); default a sphere"),
                key("velocity", K::Vec3, "initial velocity").def("[0, 0, 0]").si("m/s"),
                key("frozen", K::Bool,
                    "held grains (a rough base, a moving paddle of grains): never integrated, they keep `velocity` "
                    "(zero: fixed) and no spin, and push on the others as a wall does; pairs of frozen grains are "
                    "skipped and may overlap. Spheres and ellipsoids")
                    .def_bool(false)}});
  d.push_back({"particles.shape", "shape: {type: ellipsoid | clump, ...}",
               "The shape of a particle set. Ellipsoids use the Perram-Wertheim contact function and a "
               "quaternion rigid-body integrator; their axes scale with each particle's radius. Clumps are "
               "rigid unions of balls (sphere decompositions of a mesh); each ball is a sphere particle, the "
               "body integrates with the quaternion scheme; the set's radius is the clump's bounding radius "
               "about its centre of mass (mass ~ radius^3, inertia ~ radius^5, of the union of the balls).",
               {key("type", K::String, "shape kind").req().one_of({"sphere", "ellipsoid", "clump"}),
                key("file", K::String, "clump: a clump file written by `grains clump` (relative to the case file)"),
                key("mesh", K::String,
                    "clump: a closed mesh (.stl, .obj, .off; relative to the case file), decomposed at load time "
                    "and cached by content hash and parameters in $GRAINS_CACHE_DIR (default ~/.cache/grains/clumps)"),
                key("grid", K::Integer, "clump from mesh: grid nodes per axis of the decomposition (m = grid^3)")
                    .def("32").in(4, 1024),
                key("mu", K::Number, "clump from mesh: protrusion factor of the decomposition").def("0.25").in(0, 1),
                key("aspect_ratio", K::Number,
                    "ellipsoid of revolution a : b : b with a/b = aspect_ratio (prolate > 1, oblate < 1); the set's "
                    "radius is then the volume-equivalent radius")
                    .in(0, 1000, true),
                key("semi_axes", K::Vec3,
                    "semi-axes ratios a : b : c; the set's radius is the largest semi-axis")
                    .in(0, inf, true),
                key("orientation", K::String, "'random' (uniform) or a unit quaternion [w, x, y, z]").def("random")}});
  d.push_back({"particles.radius", "radius: {distribution: ..., ...}", "A particle size distribution (radii).",
               {key("distribution", K::String, "kind").req().one_of({"uniform", "normal", "lognormal", "discrete"}),
                key("min", K::Number, "smallest radius (uniform; truncation for normal/lognormal)").si("m").in(0, inf, true),
                key("max", K::Number, "largest radius (uniform; truncation for normal/lognormal)").si("m").in(0, inf, true),
                key("mean", K::Number, "mean radius (normal, lognormal)").si("m").in(0, inf, true),
                key("std", K::Number, "standard deviation of the radius (normal, lognormal)").si("m").in(0, inf),
                key("values", K::NumberList, "radii (discrete)").si("m"),
                key("weights", K::NumberList, "relative number frequencies of values (discrete)")}});
  d.push_back({"placement.random_fill", "placement: {type: random_fill, ...}",
               "Random non-overlapping fill of a box region (random sequential addition, largest first).",
               {key("type", K::String, "placement kind").req().one_of({"random_fill", "lattice", "file"}),
                key("region", K::Map, "{min: [..], max: [..]} box that holds the whole particles").req(),
                key("seed", K::Integer, "random seed").def("1").in(0, 1.8e19)}});
  d.push_back({"placement.lattice", "placement: {type: lattice, ...}", "A simple cubic lattice filling a box region.",
               {key("type", K::String, "placement kind").req().one_of({"random_fill", "lattice", "file"}),
                key("region", K::Map, "{min: [..], max: [..]}").req(),
                key("spacing", K::Number, "lattice spacing; default the largest diameter").si("m").in(0, inf, true),
                key("seed", K::Integer, "random seed for radii from a distribution").def("1").in(0, 1.8e19)}});
  d.push_back({"placement.file", "placement: {type: file, ...}",
               "Positions from a text file: one particle per line, 'x y z' or 'x y z r' (comma or space "
               "separated, # comments). With r the file's radii replace the set's radius.",
               {key("type", K::String, "placement kind").req().one_of({"random_fill", "lattice", "file"}),
                key("path", K::String, "file path, relative to the case file").req(),
                key("seed", K::Integer, "random seed for radii from a distribution").def("1").in(0, 1.8e19)}});
  d.push_back({"time", "time: {...}",
               "Time stepping: velocity Verlet with the fixed step dt, or SUNDIALS ARKODE (explicit adaptive "
               "Runge-Kutta, ERKStep) with error control, whose steps never exceed dt (outputs, neighbour "
               "checks and the step counter keep the cadence of dt). docs/integrators.md explains both.",
               {key("end", K::Number, "simulated end time").req().si("s").in(0, inf, true),
                key("dt", K::Number, "time step (give dt or dt_rayleigh); arkode: the largest step").si("s").in(0, inf, true),
                key("dt_rayleigh", K::Number,
                    "time step as a fraction of the Rayleigh time of the smallest particle; warned above 0.3 "
                    "(verlet), refused above 1")
                    .in(0, 1, true, false),
                key("integrator", K::String, "time integrator").def("verlet").one_of({"verlet", "arkode"}),
                key("rtol", K::Number, "arkode: relative tolerance of the local error").def("1e-6").in(0, 1, true, true),
                key("atol", K::Number,
                    "arkode: absolute tolerance in scene units: positions atol r, velocities atol V, angular "
                    "velocities atol V/r, quaternions atol, angular momenta atol I V/r (r the smallest radius, V "
                    "the fastest initial speed + free fall through the domain + fastest wall)")
                    .def("1e-6").in(0, 1, true, true),
                key("order", K::Integer, "arkode: order of the embedded Runge-Kutta pair (2, 3, 4, 5, 6 or 8)")
                    .def("4").in(2, 8)}});
  d.push_back({"neighbor", "neighbor: {...}",
               "Linked-cell Verlet lists, rebuilt when a particle has moved half the skin.",
               {key("skin", K::Number, "skin as a fraction of the largest particle diameter").def("0.1").in(0, 10, true),
                key("skin_per_grain", K::Bool,
                    "each grain's skin is `skin` times its own diameter (a pair's: times the sum of the radii, at "
                    "most the largest grain's skin), and each grain rebuilds the lists when it has moved half its "
                    "own skin: small grains of a wide size distribution keep short lists (docs/neighbor.md)")
                    .def("false"),
                key("sort", K::Bool, "re-sort particles by cell at each rebuild (memory locality)").def("true"),
                key("overlap_tolerance", K::Number,
                    "initial overlaps above this fraction of the smaller radius are refused")
                    .def("0.01").in(0, 1)}});
  d.push_back({"parallel", "parallel: {...}",
               "Threads and MPI ranks. Threads: set OMP_NUM_THREADS (default 1); with more than one thread force "
               "sums are ordered per particle by the partner's global id, so results do not depend on the thread "
               "count. Ranks: run under mpirun -np N; the domain is split on a grid of ranks whose cut planes "
               "follow the particles (quantiles), rebalanced when the load is uneven.",
               {key("deterministic", K::Bool,
                    "ordered force sums (by partner global id): results bitwise identical for any thread and rank "
                    "count in non-periodic scenes, and checkpoints continue bitwise on the same rank count; "
                    "always on with more than one thread. false under MPI sums in list order (about 10 % faster, "
                    "agreement to rounding)").def("true with more than one MPI rank, false in a serial run"),
                key("decomposition", K::Vec3, "rank grid [nx, ny, nz] (product = number of ranks)").def("chosen"),
                key("balance_threshold", K::Number, "rebalance when max/mean estimated work per rank (particles + their neighbour-list entries) exceeds this")
                    .def(1.1).in(1, 100)}});
  return d;
}

}  // namespace

std::vector<EffectDoc>& mutable_docs() {
  static std::vector<EffectDoc> all = [] {
    std::vector<EffectDoc> a = scene_docs();
    for (auto& x : law_docs()) a.push_back(std::move(x));
    for (auto& x : wall_docs()) a.push_back(std::move(x));
    for (auto& x : insertion_docs()) a.push_back(std::move(x));
    return a;
  }();
  return all;
}

const std::vector<EffectDoc>& effect_docs() { return mutable_docs(); }

void register_effect_doc(EffectDoc d) {
  for (auto& e : mutable_docs())
    if (e.name == d.name) {
      e = std::move(d);
      return;
    }
  mutable_docs().push_back(std::move(d));
}

}  // namespace grains::sim
