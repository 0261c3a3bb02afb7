// Case-file keys of the insertion effect (insert[]), declared beside its code.
#include <limits>

#include "sim/keys/effect_doc.hpp"

namespace grains::sim {

std::vector<EffectDoc> insertion_docs() {
  const double inf = std::numeric_limits<double>::infinity();
  using K = KeyType;
  std::vector<EffectDoc> d;
  d.push_back(
      {"insert", "insert: [ {...}, ... ]",
       "Inserts new grains during the run where they overlap nothing: no other grain, no wall, no grain inserted "
       "before them (checked exactly: sphere distances, the Perram-Wertheim function for ellipsoids, the balls of "
       "clumps). The grains are described as a particle set (material, radius, shape, velocity). method: fft "
       "computes the overlap volume of the grain (inflated by a margin) with the whole scene at every node of a "
       "grid over the region (clumps that turn: one field per trial orientation; ellipsoids that turn: one of their core), by a "
       "correlation in Fourier space (the "
       "configuration-space obstacle, docs/nfft.md), and visits the nodes where it vanishes in random order; "
       "method: random tries uniform random positions. fft pays off where free space is scarce and the budget "
       "exceeds its first field (in a jammed bed it placed more spheres and ellipsoids than random trials at "
       "every budget from 1 s, a field there taking 0.2-0.6 s); random trials need no field: they win with "
       "shorter budgets and cost less where free space is plentiful (measured: bench/RESULTS.md). Insertions happen at the end of a step (they show in its frame and "
       "checkpoint); a restarted run inserts what the uninterrupted run does. Not with time.integrator: arkode.",
       {key("name", K::String, "label").def("insert<k>"),
        key("material", K::String, "material name").req(),
        key("radius", K::Number, "a radius (number) or a size distribution (map, see particles.radius)")
            .req().si("m").in(0, inf, true),
        key("shape", K::Map, "grain shape as for particle sets (see particles.shape); default a sphere"),
        key("velocity", K::Vec3, "initial velocity").def("[0, 0, 0]").si("m/s"),
        key("count", K::Integer, "grains asked for at each insertion").req().in(1, 1e9),
        key("region", K::Map, "{min: [..], max: [..]} box that holds the whole inserted grains (inside the domain)")
            .req(),
        key("method", K::String, "how free positions are found").def("fft").one_of({"fft", "random"}),
        key("at", K::Number, "time of the first insertion; 0: at the end of the first step").def("0").si("s").in(0, inf),
        key("every", K::Number, "time between insertions; absent: insert once").si("s").in(0, inf, true),
        key("until", K::Number, "no insertion after this time").def("the end").si("s").in(0, inf, true),
        key("times", K::Integer,
            "insertions at most (with every): e.g. a deposit of exactly times x count grains, whatever the "
            "rounding of every to whole time steps")
            .def("no limit")
            .in(1, 1e12),
        key("orientations", K::Integer,
            "fft: trial orientations, one overlap field each, per round (clumps with random orientation; "
            "ellipsoids that turn use one field of their core, the ball of the smallest semi-axis, and "
            "draw each trial's orientation at random)")
            .def("8").in(1, 1000),
        key("spacing", K::Number, "fft: grid spacing of the candidate positions; default a quarter of the radius of "
                                  "the grain's largest ball (a sphere: its radius; ellipsoids: of their ball cover)")
            .si("m").in(0, inf, true),
        key("margin", K::Number,
            "fft: the grain's balls are inflated by margin x the radius of its largest ball, so that free nodes "
            "read as zero overlap with room to spare for the truncation error")
            .def("0.25").in(0, 10, true),
        key("mode_factor", K::Number, "fft: Fourier modes per axis / grid nodes per axis (accuracy of the field)")
            .def("1").in(0.25, 8),
        key("attempts", K::Integer, "random: consecutive failed trial positions before giving up").def("100000")
            .in(1, 1e12),
        key("budget", K::Number,
            "wall-clock time allowed per insertion (results then depend on the machine's speed); absent: none")
            .si("s").in(0, inf, true),
        key("seed", K::Integer, "random seed (positions, orientations, sizes)").def("1").in(0, 1.8e19)}});
  return d;
}

}  // namespace grains::sim
