#ifndef FSE_SIM_CONTACT_PERSISTENT_PLACES_H
#define FSE_SIM_CONTACT_PERSISTENT_PLACES_H

// The places that hold a pair of bodies in the exact model, kept across steps (docs/scenes.md →
// "Persistent places"). A place is a material point of each body, born from the library's
// contact region (fse::contactManifold): a's point on its surface and b's straight below it
// along the pair's normal, with an offset, how far it stood beyond the pair's distance at its
// birth (at most the two caps of the region, twice the patch tolerance). The solver holds
// its separation less the offset, so that a face resting within the patch tolerance of another
// is held as a whole at the pose it was found in: a tilt away from that pose is resisted
// rather than declared level again at the next detection, which let a body creep and turn step
// by step. Static friction holds the two points over each other (contact/rigid_contact.h,
// RigidContact::anchored), so that a resting body does not creep either.
// A place lives while its two points stay over each other (they drift apart when the bodies
// slide, and the place is born again where they are) and within the patch tolerance of the
// region's deepest place; the region's places that no living place stands near are born, and
// the places are then reduced to the deepest and those that span the most area.

#include <fcl_superellipsoid/contact_manifold.h>

#include <Eigen/Core>
#include <vector>

#include "contact/rigid_contact.h"
#include "model/rigid_body.h"

namespace fse_sim {

struct PersistentPlace {
  Eigen::Vector3d r_a{0, 0, 0}, r_b{0, 0, 0};  ///< body frames
  double offset = 0;                           ///< m, ≥ 0
};

/// A pair's places and the normal they hold along, kept in a's frame: a fresh region's normal
/// differs from one step to the next by the rounding of the pair's search (on flat faces, where
/// the witnesses are one of many, by 1e-4 rad and more), which at a place a quarter metre off
/// would move its separation by the contact's skin.
struct PairPlaces {
  std::vector<PersistentPlace> places;
  Eigen::Vector3d normal_a{0, 0, 0};  ///< a separates along it; a's frame; 0: none yet
  /// The library's warm start for the pair's next region (fse::ManifoldWarmStart).
  fcl_superellipsoid::ManifoldWarmStart<double> warm;
};

/// The pair's places after this step's region, and their contacts (a = ia, b = ib; n: a
/// separates along it) appended to `out`. `normal`: the pair's (a separates along it), held
/// while within the region's of it; `tolerance`: the patch tolerance the places are held
/// within (the region may have been found with a larger one). `kept` holds the previous step's
/// places of the same pair (empty for a new pair) and is updated. At most `max_places` places.
void updatePlaces(const RigidBody& a, int ia, const RigidBody& b, int ib,
                  const fcl_superellipsoid::ContactManifold<double>& region,
                  const Eigen::Vector3d& normal, double tolerance, int max_places, PairPlaces& kept,
                  std::vector<RigidContact>& out);

}  // namespace fse_sim

#endif  // FSE_SIM_CONTACT_PERSISTENT_PLACES_H
