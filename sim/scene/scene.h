#ifndef FSE_SIM_SCENE_SCENE_H
#define FSE_SIM_SCENE_SCENE_H

// A scene as the runner sees it once its file has been read and checked (scene_loader.h):
// plain values, every one validated, nothing optional left undecided. The effects a scene
// declares are the only ones the simulation constructs (physics/cloth_simulation.h).

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace fse_sim {

/// What a scene can ask to be simulated. Each has its own parameter block in the scene file,
/// under the effect's name; a block for an effect that is not declared is an error.
enum class Effect { kGravity, kStretch, kBending, kPinning, kCollision, kFriction, kDamping };

constexpr std::array<Effect, 7> kAllEffects = {
    Effect::kGravity,   Effect::kStretch,  Effect::kBending, Effect::kPinning,
    Effect::kCollision, Effect::kFriction, Effect::kDamping};

/// The effect's name in scene files ("gravity", ...).
const char* toString(Effect effect);
/// The effect named `name`, or nothing.
std::optional<Effect> effectNamed(const std::string& name);

/// How cloth vertices meet the rigid superellipsoids (chosen per run; scene_loader.h).
enum class ContactModel {
  kExact,  ///< the library's Exact solver through its batched, culled queries (the default)
  kPaper,  ///< the same queries with the paper's method at its case-study settings
  kMesh,   ///< the superellipsoid tessellated, as an FCL BVH; signed distance to the mesh
};
const char* toString(ContactModel model);
std::optional<ContactModel> contactModelNamed(const std::string& name);

/// What a run chooses (the command line), not the scene file.
struct SimulationOptions {
  ContactModel model = ContactModel::kExact;
  int mesh_vertices = 702;  ///< kMesh: the tessellation's vertex count (the paper's display mesh)
  /// Threads for the library's batched queries and the constraint sweeps: 0 = as many as TBB
  /// offers, 1 = the calling thread only. Results are bitwise the same for any count.
  int threads = 0;
};

struct TimeSpec {
  double step = 1.0 / 60;  ///< s, one simulation step (a frame)
  int substeps = 10;       ///< XPBD substeps per step, one constraint iteration each
  double duration = 1;     ///< s simulated
};

/// A rectangular cloth in a horizontal plane (normal +z), vertex (i, j) at index i + nx·j.
struct ClothSpec {
  int nx = 2, ny = 2;                 ///< vertices along x and y (≥ 2 each)
  double size_x = 1, size_y = 1;      ///< m
  Eigen::Vector3d centre{0, 0, 0};    ///< m, world frame
  double mass = 1;                    ///< kg, the whole cloth, shared equally by its vertices
  Eigen::Vector3d velocity{0, 0, 0};  ///< m/s, initial velocity of every vertex
};

/// A rigid superellipsoid (fixed in space for this issue).
struct ShapeSpec {
  Eigen::Vector3d radii{1, 1, 1};
  double eps1 = 1, eps2 = 1;
  Eigen::Vector3d position{0, 0, 0};      ///< m
  Eigen::Vector3d rotation_deg{0, 0, 0};  ///< about x, then y, then z (fixed axes), degrees
};

struct GravitySpec {
  Eigen::Vector3d acceleration{0, 0, -9.81};  ///< m/s²
};
/// XPBD compliance α (m/N): 0 is a hard constraint.
struct ComplianceSpec {
  double compliance = 0;
};
struct AttachmentSpec {
  int vertex = 0;
  Eigen::Vector3d target{0, 0, 0};  ///< m, world frame
  double compliance = 0;
};
struct PinningSpec {
  std::vector<int> fixed;                ///< vertices that never move (inverse mass 0)
  std::vector<AttachmentSpec> attached;  ///< vertices held to a point by a spring
};
struct CollisionSpec {
  double tolerance = 0.025;  ///< m: contact shell, and the most a vertex may end a step inside
};
struct FrictionSpec {
  double dynamic = 0.3;  ///< Coulomb coefficient while sliding
  double static_ = 0.4;  ///< a contact whose tangential slip fits under μs·(normal push) sticks
};
struct DampingSpec {
  double linear = 0.1;  ///< 1/s: velocities decay as exp(−linear·t)
};

struct Scene {
  std::string name;
  std::string description;
  std::vector<Effect> effects;  ///< as declared, no duplicates
  TimeSpec time;
  ClothSpec cloth;
  std::vector<ShapeSpec> shapes;
  // One block per effect, present exactly when the effect is declared.
  std::optional<GravitySpec> gravity;
  std::optional<ComplianceSpec> stretch;
  std::optional<ComplianceSpec> bending;
  std::optional<PinningSpec> pinning;
  std::optional<CollisionSpec> collision;
  std::optional<FrictionSpec> friction;
  std::optional<DampingSpec> damping;

  bool has(Effect effect) const;
};

}  // namespace fse_sim

#endif  // FSE_SIM_SCENE_SCENE_H
