#ifndef FSE_SIM_PHYSICS_PHASES_H
#define FSE_SIM_PHYSICS_PHASES_H

// The phases of a step, timed separately: the reference paper's (Tables 5–7) plus
// "contact constraints" (our positional contacts; the paper's host library has none).

#include <array>
#include <chrono>
#include <vector>

namespace fse_sim {

enum class Phase {
  kIntegration,          ///< semi-implicit Euler: gravity, predicted positions (always)
  kPositionConstraints,  ///< stretch, bending, attachments
  kContactConstraints,   ///< vertices onto their contact planes (collision), static friction
  kVelocityUpdate,       ///< v = (x − x_start) / h (always)
  kVelocityConstraints,  ///< dynamic friction, damping
  kCollisionDetection,   ///< the contact model's queries (collision)
  kTotal,                ///< the whole step (always)
};
constexpr int kPhaseCount = 7;
constexpr std::array<Phase, kPhaseCount> kAllPhases = {
    Phase::kIntegration,    Phase::kPositionConstraints, Phase::kContactConstraints,
    Phase::kVelocityUpdate, Phase::kVelocityConstraints, Phase::kCollisionDetection,
    Phase::kTotal};

/// "time integration", ... as in the paper's tables.
const char* toString(Phase phase);
/// "integration", ...: a column name for CSV files.
const char* columnName(Phase phase);

/// Seconds spent per phase in one step.
using PhaseTimes = std::array<double, kPhaseCount>;

/// Adds the time from construction to destruction to times[phase].
class ScopedPhase {
 public:
  ScopedPhase(PhaseTimes& times, Phase phase)
      : times_(times), phase_(phase), start_(std::chrono::steady_clock::now()) {}
  ~ScopedPhase() {
    times_[int(phase_)] +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  PhaseTimes& times_;
  Phase phase_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_PHASES_H
