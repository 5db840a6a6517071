#ifndef FSE_SIM_MODEL_SCENE_H
#define FSE_SIM_MODEL_SCENE_H

// A scene as the runner sees it once its file has been read and checked (scene_loader.h):
// plain values, every one validated, nothing optional left undecided. The effects a scene
// declares are the only ones the simulation constructs (physics/cloth_simulation.h).

#include <Eigen/Core>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fse_sim {

/// A scene that cannot be used: the message names the file position or JSON path.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a scene can ask to be simulated. Each has its own parameter block in the scene file,
/// under the effect's name; a block for an effect that is not declared is an error.
enum class Effect {
  kGravity,
  kStretch,
  kBending,
  kPinning,
  kCollision,
  kFriction,
  kDamping,
  kRigidBodies,
  kRigidContact,
  kRestitution
};

constexpr std::array<Effect, 10> kAllEffects = {
    Effect::kGravity,      Effect::kStretch,    Effect::kBending, Effect::kPinning,
    Effect::kCollision,    Effect::kFriction,   Effect::kDamping, Effect::kRigidBodies,
    Effect::kRigidContact, Effect::kRestitution};

/// The effect's name in scene files ("gravity", ...).
const char* toString(Effect effect);
/// The effect named `name`, or nothing.
std::optional<Effect> effectNamed(const std::string& name);

/// How cloth vertices meet the rigid superellipsoids, and rigid bodies each other (chosen per
/// run; scene_loader.h).
enum class ContactModel {
  kExact,     ///< cloth: the library's Exact solver through its batched, culled queries (the
              ///< default); rigid bodies: the library's exact superellipsoid–superellipsoid pair
  kPaper,     ///< the same vertex queries with the paper's method at its case-study settings
  kMesh,      ///< the superellipsoid tessellated, as an FCL BVH; signed distance to the mesh
  kVertices,  ///< rigid bodies: each body's mesh vertices against the other's implicit
              ///< surface, both ways, with the Exact solver (the paper's contact model)
};
const char* toString(ContactModel model);
std::optional<ContactModel> contactModelNamed(const std::string& name);

/// What a run chooses (the command line), not the scene file.
struct SimulationOptions {
  ContactModel model = ContactModel::kExact;
  int mesh_vertices = 702;  ///< cloth, kMesh: the tessellation's vertex count (the paper's display
                            ///< mesh); rigid bodies use RigidBodiesSpec::mesh_vertices
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

/// A superellipsoid: a fixed shape of a cloth scene, or a rigid body's geometry and initial pose.
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

/// A rigid superellipsoid body of a `rigid_bodies` scene.
struct BodySpec {
  ShapeSpec shape;                            ///< its geometry and initial pose
  Eigen::Vector3d velocity{0, 0, 0};          ///< m/s
  Eigen::Vector3d angular_velocity{0, 0, 0};  ///< rad/s, world frame
  bool fixed = false;                         ///< never moves (infinite mass)
};
/// Bodies drawn from a seed (the paper's chain of random superellipsoids), their centres on a
/// helix around a vertical axis: body i at start + (r·cos(i·turn), r·sin(i·turn), i·rise).
struct BodyGenerator {
  int count = 0;
  unsigned seed = 1;
  std::pair<double, double> radii{0.5, 0.6};      ///< each radius uniform in this range, m
  std::pair<double, double> exponents{0.1, 1.9};  ///< each exponent uniform in this range
  Eigen::Vector3d start{0, 0, 0};                 ///< m, the helix's axis at the first body
  double helix_radius = 0;                        ///< m (0: a vertical column)
  double turn_deg = 0;                            ///< degrees about the axis per body
  double rise = 1.25;                             ///< m up per body
};
struct RigidBodiesSpec {
  double density = 1000;    ///< kg/m³, every body
  int mesh_vertices = 506;  ///< each body's tessellation (the `vertices` and `mesh` models)
  std::optional<BodyGenerator> generate;
  std::vector<BodySpec> bodies;  ///< the listed bodies, then the generated ones
};
/// A fixed bowl: a closed hemispherical shell (opening up) generated from its sizes, or a
/// triangle mesh read from an OBJ file.
struct BowlSpec {
  double radius = 3;                  ///< m, inner
  double thickness = 0.25;            ///< m
  int rings = 25, segments = 100;     ///< per face: 2·(1 + rings·segments) vertices in all
  std::string obj;                    ///< instead of the generated shell, if not empty
  Eigen::Vector3d position{0, 0, 0};  ///< m: where the bowl's centre (of its sphere) goes
};
struct RigidContactSpec {
  double tolerance = 0.015;  ///< m: contact shell, and the most bodies may interpenetrate
};
struct RestitutionSpec {
  double coefficient = 0.3;  ///< normal speed kept after an impact, [0, 1]
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
  std::optional<RigidBodiesSpec> rigid_bodies;
  std::optional<RigidContactSpec> rigid_contact;
  std::optional<RestitutionSpec> restitution;
  std::optional<BowlSpec> bowl;  ///< rigid-body scenes only

  /// A cloth scene (cloth + fixed shapes) or a rigid-body scene (`rigid_bodies`, no cloth).
  bool isRigid() const { return rigid_bodies.has_value(); }
  bool has(Effect effect) const;
};

}  // namespace fse_sim

#endif  // FSE_SIM_MODEL_SCENE_H
