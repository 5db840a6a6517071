#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_REGION_BODIES_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_REGION_BODIES_H

// Internal: the geometries the contact region (contact_region.h) is built for, each as a
// RegionBody: its support point and its extent along a line, posed in the world.
//   superellipsoid   support in closed form; extent by Newton on the gauge along the line,
//                    from outside (the gauge is convex there, so the iterates only fall)
//   sphere, ellipsoid  closed forms
//   box, convex, triangle  the best vertex; the extent over the faces' planes
//   capsule, cylinder  closed forms (within the radius of the axis, within the slab of its
//                    length; a capsule's end balls)
//   cone             the apex or a rim point; the extent within the slab and inside the side's
//                    quadratic
//   halfspace, plane  the halfspace the hit's normal leaves (a plane's side the shape is
//                    pushed to): its boundary through the hit's point on it

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <memory>

#include "narrowphase/contact_region.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const Superellipsoid<S>& shape,
                                          const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Sphere<S>& sphere,
                                          const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Ellipsoid<S>& ellipsoid,
                                          const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Box<S>& box, const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Convex<S>& convex,
                                          const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::TriangleP<S>& triangle,
                                          const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Capsule<S>& capsule,
                                          const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Cylinder<S>& cylinder,
                                          const fcl::Transform3<S>& X);
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Cone<S>& cone, const fcl::Transform3<S>& X);
/// The halfspace that the shape leaves along the hit's normal, bounded by the plane through
/// the hit's point on the other geometry.
template <typename S>
std::unique_ptr<RegionBody<S>> flatRegionBody(const PairHit<S>& hit);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_REGION_BODIES_H
