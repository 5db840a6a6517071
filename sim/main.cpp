// fse_sim: runs a scene file (docs/scenes.md). For each contact model asked for, and for the
// Bullet peer, it steps the scene, times every phase, measures penetration and contact error
// against the exact surfaces, and writes the results under --out:
//   OUT/run.json                 the scene, the machine, every run's summary
//   OUT/<model>/steps.csv        one row per step
//   OUT/<model>/frames/*.obj     the cloth at the snapshot times; OUT/shapes.obj the shapes
// A scene with a mistake is refused (exit 2) before anything is written.

#include <fcl_superellipsoid/batch_distance.h>
#include <fcl_superellipsoid/tessellation.h>
#include <sys/utsname.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "peer/bullet_bodies.h"
#include "peer/bullet_cloth.h"
#include "physics/cloth_simulation.h"
#include "physics/rigid_simulation.h"
#include "progress_bar.h"
#include "report/measurements.h"
#include "report/run_output.h"
#include "scene/scene_loader.h"

namespace fs = std::filesystem;
namespace fse = fcl_superellipsoid;
using namespace fse_sim;

namespace {

struct Options {
  std::string scene_path;
  std::vector<std::string> models{"exact"};
  bool peer = false;
  int mesh_vertices = 702;
  int threads = 0;
  std::string out = "out/scene";
  std::vector<double> snapshots;
  double duration = 0;  // 0: the scene's
};

std::string frameName(double t) {
  char name[32];
  std::snprintf(name, sizeof name, "cloth_%07.3f.obj", t);
  return name;
}

/// Indices of the steps whose end is the first at or after each snapshot time.
std::vector<long> snapshotSteps(const std::vector<double>& times, const Scene& scene) {
  std::vector<long> steps;
  for (double t : times) steps.push_back(long(std::ceil(t / scene.time.step - 1e-9)));
  return steps;
}

void writeShapes(const Scene& scene, const std::string& path) {
  std::ofstream out(path);
  out.precision(9);
  int offset = 1;
  for (const ShapeSpec& spec : scene.shapes) {
    const fse::TriangleMesh<double> mesh = fse::tessellate(makeShape(spec), 702);
    const Eigen::Isometry3d pose = shapePose(spec);
    for (const auto& v : mesh.vertices) {
      const Eigen::Vector3d w = pose * v;
      out << "v " << w[0] << ' ' << w[1] << ' ' << w[2] << '\n';
    }
    for (const auto& t : mesh.triangles) {
      out << "f " << t[0] + offset << ' ' << t[1] + offset << ' ' << t[2] + offset << '\n';
    }
    offset += int(mesh.vertices.size());
  }
  if (!out) throw std::runtime_error(path + ": cannot be written");
}

RunSummary runModel(const Scene& scene, ContactModel model, const Options& options, long steps,
                    const fs::path& dir, fse::support::ProgressBar& progress) {
  SimulationOptions contact;
  contact.model = model;
  contact.mesh_vertices = options.mesh_vertices;
  contact.threads = options.threads;
  ClothSimulation sim(scene, contact);
  const Measurer measurer(scene);
  fs::create_directories(dir / "frames");
  const std::vector<long> snapshot = snapshotSteps(options.snapshots, scene);
  std::vector<StepRecord> records;
  records.reserve(std::size_t(steps));
  if (std::count(snapshot.begin(), snapshot.end(), 0L)) {
    writeClothObj((dir / "frames" / frameName(0)).string(), sim.mesh(), sim.positions());
  }
  for (long s = 1; s <= steps; ++s) {
    sim.step();
    records.push_back(measurer.measure(sim));
    if (std::count(snapshot.begin(), snapshot.end(), s)) {
      writeClothObj((dir / "frames" / frameName(sim.time())).string(), sim.mesh(), sim.positions());
    }
    progress.advance(1, std::string(toString(model)) + ", t = " + std::to_string(sim.time()));
  }
  writeStepsCsv((dir / "steps.csv").string(), sim.phases(), records);
  return summarize(toString(model), sim.phases(), records);
}

/// The bodies at one moment as one OBJ file (each body's tessellation at its pose).
void writeBodiesObj(const std::string& path, const std::vector<RigidBody>& bodies) {
  std::ofstream out(path);
  out.precision(7);
  int offset = 1;
  for (const RigidBody& body : bodies) {
    const fse::TriangleMesh<double> mesh = fse::tessellate(*body.shape, 162);
    for (const auto& v : mesh.vertices) {
      const Eigen::Vector3d w = body.toWorld(v);
      out << "v " << w[0] << ' ' << w[1] << ' ' << w[2] << '\n';
    }
    for (const auto& t : mesh.triangles) {
      out << "f " << t[0] + offset << ' ' << t[1] + offset << ' ' << t[2] + offset << '\n';
    }
    offset += int(mesh.vertices.size());
  }
  if (!out) throw std::runtime_error(path + ": cannot be written");
}

void writeStaticMeshObj(const std::string& path, const StaticMesh& mesh) {
  std::ofstream out(path);
  out.precision(9);
  for (Eigen::Index i = 0; i < mesh.vertices.cols(); ++i) {
    out << "v " << mesh.vertices(0, i) << ' ' << mesh.vertices(1, i) << ' ' << mesh.vertices(2, i)
        << '\n';
  }
  for (const auto& t : mesh.triangles) {
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  if (!out) throw std::runtime_error(path + ": cannot be written");
}

std::string bodiesFrameName(double t) {
  char name[32];
  std::snprintf(name, sizeof name, "bodies_%07.3f.obj", t);
  return name;
}

/// Steps a rigid-body scene's simulation (ours, any model, or the Bullet peer) and measures it
/// on the exact surfaces after every step, outside the timed step.
template <typename Simulation>
RunSummary runRigid(Simulation& sim, const std::string& name, const Scene& scene,
                    const Options& options, long steps, const fs::path& dir,
                    fse::support::ProgressBar& progress) {
  fs::create_directories(dir / "frames");
  const std::vector<long> snapshot = snapshotSteps(options.snapshots, scene);
  const double tolerance = scene.rigid_contact ? scene.rigid_contact->tolerance : 0.0;
  std::vector<StepRecord> records;
  records.reserve(std::size_t(steps));
  if (std::count(snapshot.begin(), snapshot.end(), 0L)) {
    writeBodiesObj((dir / "frames" / bodiesFrameName(0)).string(), sim.bodies());
  }
  for (long s = 1; s <= steps; ++s) {
    sim.step();
    StepRecord r;
    r.time = sim.time();
    r.seconds = sim.lastStepTimes();
    r.max_penetration = std::max(0.0, -sim.leastDistance(tolerance));
    r.contacts = sim.activeContactCount();
    r.energy = sim.energy();
    r.max_speed = sim.maxSpeed();
    records.push_back(r);
    if (std::count(snapshot.begin(), snapshot.end(), s)) {
      writeBodiesObj((dir / "frames" / bodiesFrameName(sim.time())).string(), sim.bodies());
    }
    progress.advance(1, name + ", t = " + std::to_string(sim.time()));
  }
  writeStepsCsv((dir / "steps.csv").string(), sim.phases(), records);
  RunSummary summary = summarize(name, sim.phases(), records);
  summary.bodies = int(sim.bodies().size());
  if (scene.bowl) {
    // Inside: the centre in the bowl's bounding box (for the generated bowl, its sphere below
    // the rim).
    summary.bodies_inside = 0;
    const StaticMesh& bowl = *sim.bowl();
    const Eigen::Vector3d lo = bowl.vertices.rowwise().minCoeff();
    const Eigen::Vector3d hi = bowl.vertices.rowwise().maxCoeff();
    for (const RigidBody& b : sim.bodies()) {
      const bool inside =
          scene.bowl->obj.empty()
              ? (b.x - scene.bowl->position).norm() < scene.bowl->radius &&
                    b.x[2] < scene.bowl->position[2]
              : (b.x.array() >= lo.array()).all() && (b.x.array() <= hi.array()).all();
      summary.bodies_inside += inside;
    }
  }
  return summary;
}

RunSummary runRigidModel(const Scene& scene, ContactModel model, const Options& options, long steps,
                         const fs::path& dir, fse::support::ProgressBar& progress) {
  SimulationOptions contact;
  contact.model = model;
  contact.threads = options.threads;
  RigidSimulation sim(scene, contact);
  return runRigid(sim, toString(model), scene, options, steps, dir, progress);
}

RunSummary runRigidPeer(const Scene& scene, const Options& options, long steps, const fs::path& dir,
                        fse::support::ProgressBar& progress) {
  BulletBodies peer(scene, options.threads);
  return runRigid(peer, "bullet", scene, options, steps, dir, progress);
}

RunSummary runClothPeer(const Scene& scene, const Options& options, long steps, const fs::path& dir,
                        fse::support::ProgressBar& progress) {
  BulletCloth peer(scene);
  const Measurer measurer(scene);
  const ClothMesh mesh = makeClothMesh(scene.cloth);
  fs::create_directories(dir / "frames");
  const std::vector<long> snapshot = snapshotSteps(options.snapshots, scene);
  std::vector<StepRecord> records;
  for (long s = 1; s <= steps; ++s) {
    StepRecord r;
    r.seconds[int(Phase::kTotal)] = peer.step();
    r.time = scene.time.step * double(s);
    const Eigen::Matrix3Xd x = peer.positions();
    r.max_penetration = measurer.maxPenetration(x);
    records.push_back(r);
    if (std::count(snapshot.begin(), snapshot.end(), s)) {
      writeClothObj((dir / "frames" / frameName(r.time)).string(), mesh, x);
    }
    progress.advance(1, "bullet, t = " + std::to_string(r.time));
  }
  writeStepsCsv((dir / "steps.csv").string(), {Phase::kTotal}, records);
  return summarize("bullet", {Phase::kTotal}, records);
}

std::string machine() {
  utsname u{};
  uname(&u);
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = u.machine;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

nlohmann::json sceneJson(const Scene& scene) {
  nlohmann::json effects = nlohmann::json::array();
  for (Effect e : scene.effects) effects.push_back(toString(e));
  if (scene.isRigid()) {
    const StaticMesh bowl = scene.bowl ? makeBowl(*scene.bowl) : StaticMesh{};
    return {{"name", scene.name},
            {"kind", "rigid"},
            {"effects", effects},
            {"step", scene.time.step},
            {"substeps", scene.time.substeps},
            {"duration", scene.time.duration},
            {"bodies", sceneBodies(*scene.rigid_bodies).size()},
            {"body_mesh_vertices", scene.rigid_bodies->mesh_vertices},
            {"bowl_vertices", bowl.vertices.cols()},
            {"bowl_triangles", bowl.triangles.size()},
            {"tolerance", scene.rigid_contact ? scene.rigid_contact->tolerance : 0.0}};
  }
  const ClothSpec& c = scene.cloth;
  return {{"name", scene.name},
          {"effects", effects},
          {"step", scene.time.step},
          {"substeps", scene.time.substeps},
          {"duration", scene.time.duration},
          {"kind", "cloth"},
          {"vertices", c.nx * c.ny},
          {"triangles", 2 * (c.nx - 1) * (c.ny - 1)},  // two per grid quad (cloth_mesh.h)
          {"tolerance", scene.collision ? scene.collision->tolerance : 0.0}};
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"fse_sim: runs a scene file (JSON) and writes its timings and measurements"};
  app.add_option("scene", options.scene_path, "scene file (sim/scenes/*.json)")->required();
  app.add_option("--contact", options.models,
                 "contact models to run, in order: exact paper mesh (cloth scenes); exact vertices "
                 "paper mesh (rigid-body scenes)")
      ->check(CLI::IsMember({"exact", "paper", "mesh", "vertices"}))
      ->expected(1, 4);
  app.add_flag("--peer", options.peer,
               "also run the Bullet peer (soft-body cloth; rigid bodies for rigid-body scenes)");
  app.add_option("--mesh-vertices", options.mesh_vertices,
                 "mesh model: vertices of the tessellation")
      ->check(CLI::Range(5, 1000000));
  app.add_option("--threads", options.threads, "threads of the library's batched queries (0: all)")
      ->check(CLI::Range(0, 1024));
  app.add_option("--out", options.out, "output directory (replaced)");
  app.add_option("--snapshots", options.snapshots, "times (s) at which to write the cloth as OBJ")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--duration", options.duration, "simulate this long instead (s)")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  Scene scene;
  try {
    scene = loadScene(options.scene_path);
    if (options.duration > 0) {
      requireRange(options.duration >= scene.time.step, "--duration",
                   "at least one step (" + std::to_string(scene.time.step) + " s)",
                   options.duration);
      scene.time.duration = options.duration;
      checkSteps(scene.time, "--duration");
    }
    for (const std::string& name : options.models) {
      const ContactModel model = *contactModelNamed(name);
      if (!scene.isRigid() && model == ContactModel::kVertices) {
        throw SceneError(
            "--contact vertices: a rigid-body model; cloth scenes take exact, paper "
            "or mesh");
      }
    }
  } catch (const SceneError& e) {
    std::cerr << "fse_sim: error: " << e.what() << '\n';
    return 2;
  }
  try {
    const long steps = std::lround(scene.time.duration / scene.time.step);
    const fs::path out = options.out;
    // Replace only what an earlier run wrote: never a folder of something else.
    if (fs::exists(out) && !fs::is_empty(out) && !fs::exists(out / "run.json")) {
      std::cerr << "fse_sim: error: --out " << out.string()
                << ": exists and is not an fse_sim output folder (no run.json); not replacing it\n";
      return 2;
    }
    fs::remove_all(out);
    fs::create_directories(out);
    if (!scene.shapes.empty()) writeShapes(scene, (out / "shapes.obj").string());
    if (scene.bowl) writeStaticMeshObj((out / "bowl.obj").string(), makeBowl(*scene.bowl));
    const long runs = long(options.models.size()) + (options.peer ? 1 : 0);
    fse::support::ProgressBar progress(runs * steps, true);
    nlohmann::json summaries = nlohmann::json::array();
    std::vector<RunSummary> results;
    for (const std::string& name : options.models) {
      const ContactModel model = *contactModelNamed(name);
      results.push_back(scene.isRigid()
                            ? runRigidModel(scene, model, options, steps, out / name, progress)
                            : runModel(scene, model, options, steps, out / name, progress));
    }
    if (options.peer) {
      results.push_back(scene.isRigid()
                            ? runRigidPeer(scene, options, steps, out / "bullet", progress)
                            : runClothPeer(scene, options, steps, out / "bullet", progress));
    }
    progress.finish();
    for (const RunSummary& s : results) summaries.push_back(toJson(s));
    writeJson((out / "run.json").string(), {{"scene", sceneJson(scene)},
                                            {"machine", machine()},
                                            {"simd", fse::simdInstructionSet()},
                                            {"threads", options.threads},
                                            {"runs", summaries}});
    // A short table on stdout: mean ms per phase, and penetration.
    std::printf("%-8s %10s %10s %12s %12s\n", "model", "total ms", "coll. ms", "max pen. m",
                scene.isRigid() ? "inside" : "contact err");
    for (const RunSummary& s : results) {
      std::printf("%-8s %10.3f %10.3f %12.3e ", s.model.c_str(), s.mean_ms[int(Phase::kTotal)],
                  s.mean_ms[int(Phase::kCollisionDetection)], s.max_penetration);
      if (scene.isRigid()) {
        std::printf("%9d/%d\n", s.bodies_inside, s.bodies);
      } else {
        std::printf("%12.3e\n", s.contact_error_max);
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "fse_sim: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
