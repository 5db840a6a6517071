#ifndef FSE_SIM_PHYSICS_SIMULATION_H
#define FSE_SIM_PHYSICS_SIMULATION_H

// What the cloth and the rigid simulations share: the phases a scene runs, their times per
// step, and the step itself. A step is the collision detection (once per step, where the scene
// declares contacts), then `substeps` substeps of XPBD (docs/scenes.md → "Effects"), each
// phase timed (phases.h).

#include <vector>

#include "model/scene.h"
#include "physics/phases.h"

namespace fse_sim {

class Simulation {
 public:
  virtual ~Simulation() = default;

  /// Advances by one step (Scene::time.step).
  void step();

  double time() const { return time_; }
  /// The phases this scene runs, in the paper's order; the others cost nothing.
  const std::vector<Phase>& phases() const { return phases_; }
  /// Time per phase of the last step (0 for phases not run).
  const PhaseTimes& lastStepTimes() const { return times_; }

 protected:
  explicit Simulation(const TimeSpec& time) : time_spec_(time) {}

  /// Declares the phases the scene runs: integration, the velocity update and the total
  /// always; the others where the scene's effects need them.
  void declarePhases(bool position_constraints, bool contact_constraints, bool velocity_constraints,
                     bool collision_detection);
  /// Adds the time from now to the end of the scope to the phase's time of this step.
  ScopedPhase timed(Phase phase) { return ScopedPhase(times_, phase); }

  /// The step's `n` substeps of length h; by default substep(h) n times.
  virtual void runSubsteps(int n, double h);

 private:
  /// The collision detection of a step of length h (only where it is a declared phase).
  virtual void detect(double h) = 0;
  virtual void substep(double h) = 0;

  TimeSpec time_spec_;
  std::vector<Phase> phases_;
  bool detects_ = false;
  PhaseTimes times_{};
  double time_ = 0;
  long steps_ = 0;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_SIMULATION_H
