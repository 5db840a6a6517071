#include "model/scene.h"

#include <algorithm>

namespace fse_sim {

const char* toString(Effect effect) {
  switch (effect) {
    case Effect::kGravity:
      return "gravity";
    case Effect::kStretch:
      return "stretch";
    case Effect::kBending:
      return "bending";
    case Effect::kPinning:
      return "pinning";
    case Effect::kCollision:
      return "collision";
    case Effect::kFriction:
      return "friction";
    case Effect::kDamping:
      return "damping";
    case Effect::kRigidBodies:
      return "rigid_bodies";
    case Effect::kRigidContact:
      return "rigid_contact";
    case Effect::kRestitution:
      return "restitution";
  }
  return "?";
}

std::optional<Effect> effectNamed(const std::string& name) {
  for (Effect e : kAllEffects) {
    if (name == toString(e)) return e;
  }
  return std::nullopt;
}

const char* toString(ContactModel model) {
  switch (model) {
    case ContactModel::kExact:
      return "exact";
    case ContactModel::kPaper:
      return "paper";
    case ContactModel::kMesh:
      return "mesh";
    case ContactModel::kVertices:
      return "vertices";
  }
  return "?";
}

std::optional<ContactModel> contactModelNamed(const std::string& name) {
  for (ContactModel m :
       {ContactModel::kExact, ContactModel::kPaper, ContactModel::kMesh, ContactModel::kVertices}) {
    if (name == toString(m)) return m;
  }
  return std::nullopt;
}

bool Scene::has(Effect effect) const {
  return std::find(effects.begin(), effects.end(), effect) != effects.end();
}

}  // namespace fse_sim
