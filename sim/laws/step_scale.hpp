#pragma once
// The time scale of a normal law that the time step is checked against
// (build_scene): each normal law says which it is and where the limits lie.
namespace grains::sim {

class PairTable;

/// What set-up knows of the smallest grains before placing them.
struct GrainExtremes {
  double rayleigh_time = 0;  // of the smallest grain (build_scene.hpp: rayleigh_time)
  double min_mass = 0;       // of the lightest grain (a clump: its body), kg
  double min_radius = 0;     // smallest radius of curvature (a clump: its smallest ball), m
};

struct StepScale {
  double time = 0;           // s; infinite: no limit
  const char* unit = "";     // plural, e.g. "Rayleigh times"
  const char* symbol = "";   // e.g. "T_R"
  double refuse = 1;         // dt above refuse * time is refused (Verlet)
  double warn = 0.3;         // dt above warn * time is warned about
  /// The scale is the Rayleigh time: time.dt_rayleigh (at most 1) then
  /// needs no check, and the refusal suggests it.
  bool rayleigh = false;
};

}  // namespace grains::sim
