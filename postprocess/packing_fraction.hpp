#pragma once
// Packing fraction of spheres in an axis-aligned box, exact up to quadrature
// rounding (~1e-12 relative): every sphere contributes the volume of its
// intersection with the box, so spheres cut by the region's faces count
// with exactly the part inside.
#include <vector>

#include <Eigen/Core>

namespace grains::postprocess {

using Vec3 = Eigen::Vector3d;

struct Box {
  Vec3 lo, hi;
  double volume() const { return (hi - lo).prod(); }
};

/// Area of the disk (centre (cx, cy), radius r) inside the rectangle [x0,x1] x [y0,y1].
double disk_rectangle_area(double cx, double cy, double r, double x0, double x1, double y0, double y1);
/// Volume of the sphere (c, r) inside the box.
double sphere_box_volume(const Vec3& c, double r, const Box& b);
/// Solid volume fraction of the spheres inside the box (overlaps are counted twice:
/// for DEM overlaps of a fraction of a percent this is negligible, and stated).
double packing_fraction(const std::vector<Vec3>& x, const std::vector<double>& r, const Box& b);

/// A bulk region of a poured bed: `margin` away from the container's sides
/// and floor and from the free surface, where the free surface is the height
/// below which the bed is dense (the mean of the top layer of centres).
Box bulk_region(const std::vector<Vec3>& x, const std::vector<double>& r, const Box& container, double margin);

}  // namespace grains::postprocess
