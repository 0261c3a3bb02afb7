#pragma once
// The union of a set of (overlapping) balls as a solid: a bin index for
// point queries and mass properties by adaptive octree integration, so that
// overlaps are counted once (not a sum of ball volumes or inertias).
//
// Integration: the bounding box of the union is cut into cubes; a cube that
// lies inside one ball (all 8 corners inside it) is counted whole, a cube
// that no ball reaches is dropped, any other cube is split in 8, down to
// cubes of edge `finest`. An undecided cube at the finest level is counted
// by its centre (midpoint rule). The total volume of those undecided cubes
// is returned as `volume_bound`: a strict bound on the volume error (each
// undecided cube is wrongly counted by at most its own volume), the typical
// error being far smaller because the midpoint misses cancel.

#include "contact/clump/sphere_decomposition.hpp"

#include <Eigen/Core>

#include <vector>

namespace grains::clump {

class BallUnion {
public:
  explicit BallUnion(std::vector<Ball> balls);

  const std::vector<Ball>& balls() const { return balls_; }
  // min_i (|p - c_i| - r_i): exact distance to the union for points outside
  // it, <= 0 inside it.
  double signed_distance_bound(const Eigen::Vector3d& p) const;
  bool contains(const Eigen::Vector3d& p, double tolerance = 0.0) const;
  // Balls whose bounding boxes overlap the box [lo, hi].
  void candidates(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int>& out) const;
  Eigen::Vector3d lo() const { return lo_; }
  Eigen::Vector3d hi() const { return hi_; }

private:
  std::vector<Ball> balls_;
  Eigen::Vector3d lo_, hi_;
  double bin_ = 1.0;
  int nb_[3] = {1, 1, 1};
  std::vector<std::vector<int>> bins_;
  std::vector<int> stamp_;
  mutable std::vector<int> seen_;
  mutable int tick_ = 0;
  int bin_coord(double x, int d) const;
};

struct UnionMoments {
  double volume = 0.0;
  double volume_bound = 0.0;  // strict bound on |volume error|
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // per unit density, about the centroid
  long cells = 0;                                      // octree leaves visited
};

// `finest`: edge of the smallest octree cube (e.g. 1/512 of the union's extent).
UnionMoments union_moments(const BallUnion& balls, double finest);

}  // namespace grains::clump
