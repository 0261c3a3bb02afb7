#pragma once
// The registry of wall kinds: the one place a wall kind is registered
// (wall_kind.hpp says what a kind supplies). Walls are kept by kind in this
// order, which is also the order of their near lists, history slots, output
// cells and force accumulation.
#include "sim/registry.hpp"
#include "sim/walls/cylinder_wall.hpp"
#include "sim/walls/mesh_wall.hpp"
#include "sim/walls/plane_wall.hpp"

namespace grains::sim {

using WallKinds = TypeList<PlaneWall, CylinderWall, MeshWall>;

}  // namespace grains::sim
