#ifndef FCL_SUPERELLIPSOID_BENCH_PAIRS_H
#define FCL_SUPERELLIPSOID_BENCH_PAIRS_H

#include <string>
#include <vector>

namespace fcl_superellipsoid {
namespace bench {

/// The superellipsoid against every FCL shape and another superellipsoid: our pair solvers
/// (through the front end), FCL's GJKSolver_libccd and Bullet's btGjkEpaSolver2 with the exact
/// support function, on the same pairs; time per query and error per separation bucket. Prints
/// the table; writes every bucket's row to `csv` unless it is empty. `only`: the kinds to run
/// (all if empty); the others' pairs are still drawn, so each kind's pairs stay the same.
int runPairs(int per_kind, const std::string& csv, const std::vector<std::string>& only);

/// Writes our answer to every pair that runPairs(per_kind, …) draws, with nothing timed: per
/// pair, the distance and both nearest points of fcl_superellipsoid::distance (signed), and the
/// contacts of fcl_superellipsoid::collide (up to 4, with position, normal and depth), in both
/// argument orders, as hexadecimal floats; also the same pair in float. Two builds that give
/// the same file give bitwise the same pair answers (docs/design.md → "Checking a refactoring").
int writePairAnswers(int per_kind, const std::string& path);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_PAIRS_H
