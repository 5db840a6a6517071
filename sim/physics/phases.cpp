#include "physics/phases.h"

namespace fse_sim {

const char* toString(Phase phase) {
  switch (phase) {
    case Phase::kIntegration:
      return "time integration";
    case Phase::kPositionConstraints:
      return "position constraints";
    case Phase::kContactConstraints:
      return "contact constraints";
    case Phase::kVelocityUpdate:
      return "velocity update";
    case Phase::kVelocityConstraints:
      return "velocity constraints";
    case Phase::kCollisionDetection:
      return "collision detection";
    case Phase::kTotal:
      return "total";
  }
  return "?";
}

const char* columnName(Phase phase) {
  switch (phase) {
    case Phase::kIntegration:
      return "integration";
    case Phase::kPositionConstraints:
      return "position_constraints";
    case Phase::kContactConstraints:
      return "contact_constraints";
    case Phase::kVelocityUpdate:
      return "velocity_update";
    case Phase::kVelocityConstraints:
      return "velocity_constraints";
    case Phase::kCollisionDetection:
      return "collision_detection";
    case Phase::kTotal:
      return "total";
  }
  return "?";
}

}  // namespace fse_sim
