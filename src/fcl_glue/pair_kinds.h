#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIR_KINDS_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIR_KINDS_H

// Internal: every kind of geometry the superellipsoid is paired with, one row each: the other
// geometry's node type, FCL's class of it, the check of its parameters, the narrowphase
// function that answers the pair (src/narrowphase/), the other geometry's body for the
// contact region (narrowphase/region_bodies.h) and its shape around its witness point for the
// pair's Jacobians (narrowphase/witness_feature.h). The dispatcher (pairs.cpp) and FCL's
// tables (fcl_tables.h, and through them the front end, the broadphase callbacks and the
// interposed plain calls) read this table and nothing else, so adding a pair kind is one row
// here and one file in src/narrowphase/ (docs/design.md → "Adding a pair").

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include "common/invalid_argument.h"
#include "fcl_glue/pair.h"
#include "narrowphase/capsule_pair.h"
#include "narrowphase/halfspace_pair.h"
#include "narrowphase/polytope_pair.h"
#include "narrowphase/region_bodies.h"
#include "narrowphase/round_pair.h"
#include "narrowphase/smooth_pair.h"
#include "narrowphase/sphere_pair.h"
#include "narrowphase/witness_feature.h"
#include "narrowphase/witnesses_on_bodies.h"

namespace fcl_superellipsoid {
namespace detail {

/// How a pair kind answers: one hit (a shape), or one contact per penetrating vertex (a
/// BVHModel: mesh_pair.h, which writes FCL's results itself).
enum class PairForm { kShape, kMesh };

/// A shape kind's answer: std::nullopt where the other geometry is not of the row's class (a
/// user's geometry may report any node type). `where` names the query in a refusal.
template <typename S>
using ShapeAnswer = std::optional<PairHit<S>> (*)(const Pair<S>& pair, const char* where);

/// The other geometry as a body of the contact region (narrowphase/region_bodies.h), given
/// the pair's hit; nullptr where the other geometry is not of the row's class.
template <typename S>
using RegionMaker = std::unique_ptr<RegionBody<S>> (*)(const Pair<S>& pair, const PairHit<S>& hit);

/// The other geometry's shape around its witness point (narrowphase/witness_feature.h), given
/// the pair's hit.
template <typename S>
using FeatureMaker = WitnessFeature<S> (*)(const Pair<S>& pair, const PairHit<S>& hit);

/// One pair kind.
template <typename S>
struct PairKind {
  fcl::NODE_TYPE node_type;
  PairForm form;
  ShapeAnswer<S> answer;    // kShape only
  RegionMaker<S> region;    // nullptr: no contact region yet (one contact per pair)
  FeatureMaker<S> feature;  // kShape only
};

// --- The checks of the other geometry's parameters ----------------------------------------
// Parameters that are not finite, a negative length, or a length or coordinate beyond a
// sixteenth of the largest finite value are refused: its features' coordinates, sums of a few
// of them, must stay finite (docs/hardening.md → "Bad input"). An ellipsoid's radii are held to
// the superellipsoid's largest radius (checkRadius).

template <typename S>
void checkLength(const char* where, const char* name, S v) {
  if (!(v >= S(0) && v <= std::numeric_limits<S>::max() / 16)) {
    throwInvalidArgument(
        where, std::string("the other shape's ") + name + " must be finite, >= 0 and <= max/16", v);
  }
}

/// An ellipsoid's radii: held to the superellipsoid's radius range at the top (zero radii are
/// answered), since the smooth pair that answers both works with their squares and ratios
/// (its support map, its rolling radius a²/b: docs/hardening.md, finding 22).
template <typename S>
void checkRadius(const char* where, const char* name, S v) {
  if (!(v >= S(0) && v <= NumericRange<S>::kMaxRadius)) {
    throwInvalidArgument(
        where,
        std::string("the other shape's ") + name +
            " must be finite, >= 0 and <= " + formatValue(NumericRange<S>::kMaxRadius),
        v);
  }
}

template <typename S>
void checkPoint(const char* where, const char* name, const Vector3<S>& p) {
  if (!p.allFinite() || !(p.cwiseAbs().maxCoeff() <= std::numeric_limits<S>::max() / 16)) {
    throwInvalidArgument(
        where,
        std::string("the other shape's ") + name + " must be finite, each |coordinate| <= max/16",
        p);
  }
}

template <typename S>
void checkNothing(const char*, const Superellipsoid<S>&) {}  // checked when it was constructed
template <typename S>
void checkSphere(const char* where, const fcl::Sphere<S>& x) {
  checkLength(where, "radius", x.radius);
}
template <typename S>
void checkEllipsoid(const char* where, const fcl::Ellipsoid<S>& x) {
  for (int i = 0; i < 3; ++i) checkRadius(where, "radii", x.radii[i]);
}
template <typename S>
void checkBox(const char* where, const fcl::Box<S>& x) {
  for (int i = 0; i < 3; ++i) checkLength(where, "side", x.side[i]);
}
/// A capsule, cylinder or cone.
template <typename S, typename Round>
void checkRound(const char* where, const Round& x) {
  checkLength(where, "radius", x.radius);
  checkLength(where, "lz", x.lz);
}
/// A halfspace or plane.
template <typename S, typename Plane>
void checkPlane(const char* where, const Plane& x) {
  checkPoint(where, "normal n", x.n);
  checkLength(where, "|d|", std::abs(x.d));
}
template <typename S>
void checkConvex(const char* where, const fcl::Convex<S>& x) {
  for (const Vector3<S>& v : x.getVertices()) checkPoint(where, "vertex", v);
}
template <typename S>
void checkTriangle(const char* where, const fcl::TriangleP<S>& x) {
  checkPoint(where, "vertex a", x.a);
  checkPoint(where, "vertex b", x.b);
  checkPoint(where, "vertex c", x.c);
}

/// The answer of a shape kind: the other geometry as FCL's class G, checked by Check, answered
/// by the narrowphase function Hit, its witnesses on both bodies (witnesses_on_bodies.h; a
/// halfspace's or plane's witness is on it by construction).
template <typename S, typename G, void (*Check)(const char*, const G&),
          std::optional<PairHit<S>> (*Hit)(const ShapePair<S>&, const G&)>
std::optional<PairHit<S>> shapeAnswer(const Pair<S>& pair, const char* where) {
  const G* other = geometryAs<G>(pair.other);
  if (other == nullptr) return std::nullopt;
  Check(where, *other);
  const std::optional<PairHit<S>> hit = Hit(pair, *other);
  if constexpr (std::is_same_v<G, fcl::Halfspace<S>> || std::is_same_v<G, fcl::Plane<S>>) {
    return hit;
  } else {
    if (!hit) return hit;
    return witnessesOnBodies(*pair.shape, *pair.X_WS, *regionBody(*other, *pair.X_WO), *hit);
  }
}

/// The other geometry, of FCL's class G, as a region body.
template <typename S, typename G>
std::unique_ptr<RegionBody<S>> shapeRegion(const Pair<S>& pair, const PairHit<S>&) {
  const G* other = geometryAs<G>(pair.other);
  return other != nullptr ? regionBody(*other, *pair.X_WO) : nullptr;
}
/// A halfspace or plane: the side the hit pushes the shape to (region_bodies.h).
template <typename S>
std::unique_ptr<RegionBody<S>> flatRegion(const Pair<S>&, const PairHit<S>& hit) {
  return flatRegionBody(hit);
}

/// The other geometry, of FCL's class G, around its witness point (its answer matched G).
template <typename S, typename G,
          WitnessFeature<S> (*Feature)(const G&, const fcl::Transform3<S>&, const PairHit<S>&)>
WitnessFeature<S> shapeFeature(const Pair<S>& pair, const PairHit<S>& hit) {
  return Feature(*geometryAs<G>(pair.other), *pair.X_WO, hit);
}
/// A halfspace or plane: a face.
template <typename S>
WitnessFeature<S> flatFeature(const Pair<S>&, const PairHit<S>&) {
  return faceFeature<S>();
}

// --- The table ------------------------------------------------------------------------------

template <typename S>
inline constexpr PairKind<S> kPairKinds[] = {
    // Newton on the sphere of directions (smooth_pair.h).
    {fcl::BV_UNKNOWN, PairForm::kShape,
     &shapeAnswer<S, Superellipsoid<S>, &checkNothing<S>, &superellipsoidHit<S>>,
     &shapeRegion<S, Superellipsoid<S>>,
     &shapeFeature<S, Superellipsoid<S>, &smoothFeature<S, Superellipsoid<S>>>},
    {fcl::GEOM_ELLIPSOID, PairForm::kShape,
     &shapeAnswer<S, fcl::Ellipsoid<S>, &checkEllipsoid<S>, &ellipsoidHit<S>>,
     &shapeRegion<S, fcl::Ellipsoid<S>>,
     &shapeFeature<S, fcl::Ellipsoid<S>, &smoothFeature<S, fcl::Ellipsoid<S>>>},
    // The point solver (sphere_pair.h); one support point (halfspace_pair.h).
    {fcl::GEOM_SPHERE, PairForm::kShape,
     &shapeAnswer<S, fcl::Sphere<S>, &checkSphere<S>, &sphereHit<S>>,
     &shapeRegion<S, fcl::Sphere<S>>,
     &shapeFeature<S, fcl::Sphere<S>, &smoothFeature<S, fcl::Sphere<S>>>},
    {fcl::GEOM_HALFSPACE, PairForm::kShape,
     &shapeAnswer<S, fcl::Halfspace<S>, &checkPlane<S, fcl::Halfspace<S>>, &halfspaceHit<S>>,
     &flatRegion<S>, &flatFeature<S>},
    {fcl::GEOM_PLANE, PairForm::kShape,
     &shapeAnswer<S, fcl::Plane<S>, &checkPlane<S, fcl::Plane<S>>, &planeHit<S>>, &flatRegion<S>,
     &flatFeature<S>},
    // Features (capsule_pair.h, polytope_pair.h, round_pair.h).
    {fcl::GEOM_CAPSULE, PairForm::kShape,
     &shapeAnswer<S, fcl::Capsule<S>, &checkRound<S, fcl::Capsule<S>>, &capsuleHit<S>>,
     &shapeRegion<S, fcl::Capsule<S>>, &shapeFeature<S, fcl::Capsule<S>, &capsuleFeature<S>>},
    {fcl::GEOM_BOX, PairForm::kShape, &shapeAnswer<S, fcl::Box<S>, &checkBox<S>, &boxHit<S>>,
     &shapeRegion<S, fcl::Box<S>>, &shapeFeature<S, fcl::Box<S>, &boxFeature<S>>},
    {fcl::GEOM_CONVEX, PairForm::kShape,
     &shapeAnswer<S, fcl::Convex<S>, &checkConvex<S>, &convexHit<S>>,
     &shapeRegion<S, fcl::Convex<S>>, &shapeFeature<S, fcl::Convex<S>, &convexFeature<S>>},
    {fcl::GEOM_TRIANGLE, PairForm::kShape,
     &shapeAnswer<S, fcl::TriangleP<S>, &checkTriangle<S>, &triangleHit<S>>,
     &shapeRegion<S, fcl::TriangleP<S>>, &shapeFeature<S, fcl::TriangleP<S>, &triangleFeature<S>>},
    {fcl::GEOM_CYLINDER, PairForm::kShape,
     &shapeAnswer<S, fcl::Cylinder<S>, &checkRound<S, fcl::Cylinder<S>>, &cylinderHit<S>>,
     &shapeRegion<S, fcl::Cylinder<S>>, &shapeFeature<S, fcl::Cylinder<S>, &cylinderFeature<S>>},
    {fcl::GEOM_CONE, PairForm::kShape,
     &shapeAnswer<S, fcl::Cone<S>, &checkRound<S, fcl::Cone<S>>, &coneHit<S>>,
     &shapeRegion<S, fcl::Cone<S>>, &shapeFeature<S, fcl::Cone<S>, &coneFeature<S>>},
    // FCL's BVH models of the eight BV types: their vertices (mesh_pair.h).
    {fcl::BV_AABB, PairForm::kMesh, nullptr, nullptr, nullptr},
    {fcl::BV_OBB, PairForm::kMesh, nullptr, nullptr, nullptr},
    {fcl::BV_RSS, PairForm::kMesh, nullptr, nullptr, nullptr},
    {fcl::BV_kIOS, PairForm::kMesh, nullptr, nullptr, nullptr},
    {fcl::BV_OBBRSS, PairForm::kMesh, nullptr, nullptr, nullptr},
    {fcl::BV_KDOP16, PairForm::kMesh, nullptr, nullptr, nullptr},
    {fcl::BV_KDOP18, PairForm::kMesh, nullptr, nullptr, nullptr},
    {fcl::BV_KDOP24, PairForm::kMesh, nullptr, nullptr, nullptr},
};

/// The row of node type t, or nullptr where the superellipsoid has no pair with it.
template <typename S>
const PairKind<S>* findPairKind(fcl::NODE_TYPE t) {
  static constexpr std::array<int, fcl::NODE_COUNT> kRowOf = [] {
    std::array<int, fcl::NODE_COUNT> row{};
    for (int& r : row) r = -1;
    int k = 0;
    for (const PairKind<S>& kind : kPairKinds<S>) row[kind.node_type] = k++;
    return row;
  }();
  if (t < 0 || t >= fcl::NODE_COUNT || kRowOf[t] < 0) return nullptr;
  return &kPairKinds<S>[kRowOf[t]];
}

/// FCL's name of a node type, for a refusal.
inline std::string nodeTypeName(fcl::NODE_TYPE t) {
  static const char* const kNames[] = {
      "BV_UNKNOWN",  "BV_AABB",        "BV_OBB",         "BV_RSS",        "BV_kIOS",
      "BV_OBBRSS",   "BV_KDOP16",      "BV_KDOP18",      "BV_KDOP24",     "GEOM_BOX",
      "GEOM_SPHERE", "GEOM_ELLIPSOID", "GEOM_CAPSULE",   "GEOM_CONE",     "GEOM_CYLINDER",
      "GEOM_CONVEX", "GEOM_PLANE",     "GEOM_HALFSPACE", "GEOM_TRIANGLE", "GEOM_OCTREE"};
  const int i = static_cast<int>(t);
  return i >= 0 && i < int(sizeof(kNames) / sizeof(kNames[0])) ? kNames[i] : std::to_string(i);
}

/// The refusal of a partner that is not one of the shape kinds above (a mesh, an octree, a
/// user's geometry), by the calls that answer one pair of shapes (contact_manifold.h,
/// pair_derivatives.h).
template <typename S>
[[noreturn]] void throwUnsupportedPartner(const char* where,
                                          const fcl::CollisionGeometry<S>& other) {
  throwInvalidArgument(where,
                       "the other geometry must be a Superellipsoid, fcl::Sphere, Ellipsoid, Box, "
                       "Convex, TriangleP, Capsule, Cylinder, Cone, Halfspace or Plane (its node "
                       "type)",
                       nodeTypeName(other.getNodeType()));
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIR_KINDS_H
