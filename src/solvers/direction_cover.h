#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_DIRECTION_COVER_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_DIRECTION_COVER_H

// Internal: a cover of the first octant's unit directions by cells, each with the shape's
// support point in its centre direction, built once per shape (directionCover(shape), below).
// The Exact solver uses it inside the shape for two things (docs/math.md → "The direction
// cover"):
//
//  - a first start: the depth of Q is min over unit n of F(n) = h(n) − n·Q (h the support
//    function), and F at a cell's centre a, a·(s(a) − Q), is an upper bound of it; the cell
//    where it is smallest is usually where the nearest point's normal lies.
//  - half of a certificate that a converged answer is the global one: every point s of the
//    shape gives h(n) ≥ n·s, so over a cell of half-angle θ around a, with w = s(a) − Q at the
//    angle φ from a, F(n) ≥ ‖w‖·cos(φ + θ). The cells where that bound stays below the
//    answer's distance (refined three levels deep) lie within `cap`'s radius of its normal; the
//    other half, ball_certificate.h's Hessian bound over the surface near the answer, covers
//    them. Where that cap is too wide for the Hessian bound, `capWithin` splits the cells
//    beyond a smaller radius further, with support points evaluated per query.
//
// Cells: the first octant's directions, mapped onto the three faces of the unit cube (the face
// of the largest component), each face a k × k grid; k = 4, 8, 16 on the three stored levels
// (32, 64, 128 split per query), a cell of one level the union of four of the next. The cells'
// geometry does not depend on the shape (built once per process); their support points do, and
// are evaluated on first use, four siblings at a time, so that a query reads only what it needs:
// a start evaluates 56 of them, a certificate near the surface the few dozen cells near the
// answer's normal, and a new shape costs its first queries little more than its later ones.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"
#include "shape/nested_norm.h"
#include "shape/shape_caches.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
class DirectionCover {
 public:
  /// The coarsest grid per cube face, and the number of levels (each halves the cells' size).
  static constexpr int kCoarse = 4;
  static constexpr int kLevels = 3;
  /// The finest level's cells per face side, and its number of cells (three faces).
  static constexpr int kFinestSide = kCoarse << (kLevels - 1);
  static constexpr std::size_t kFinestCells = 3 * std::size_t(kFinestSide) * kFinestSide;

  /// The cover of `shape`, with no support point evaluated yet. A cell's (in its centre
  /// direction, pulled toward the centre by a few ulps so that it lies inside the shape despite
  /// rounding: the bounds need points of the shape, not near it) is evaluated with its three
  /// siblings when a query first reads it; likewise the first split grid's (splitSupport).
  /// Thread-safe: each group is evaluated once, by the first thread that reads it.
  explicit DirectionCover(const Superellipsoid<S>& shape);

  /// A first-octant surface point whose normal lies near the nearest point's normal for a point
  /// y inside the shape (first octant): the support point of the finest cell reached by
  /// descending, level by level, into the child of smallest F(a) = a·(s(a) − y).
  Vector3<S> startNear(const Vector3<S>& y) const;

  /// For y in the first octant, a unit n_star in it and a length `need`: a chord radius θ such
  /// that every first-octant unit direction n with F(n) = h(n) − n·y < need satisfies
  /// ‖n − n_star‖ ≤ θ, with the finest level's failing cells behind it (for capWithin). Cells
  /// whose lower bound of F reaches `need` are skipped, the others refined down to the finest
  /// level and counted whole. θ is +∞ as soon as it exceeds `limit`, and where y or need is not
  /// finite.
  struct Cap {
    S radius;           // θ; +∞ beyond the limit
    std::size_t count;  // the finest level's failing cells, in `failing`
    std::array<std::uint16_t, kFinestCells> failing;
  };
  Cap cap(const Vector3<S>& y, const Vector3<S>& n_star, S need, S limit) const;

  /// Whether the same claim holds with the radius `target`, smaller than the cap's: the finest
  /// failing cells that reach beyond `target` from n_star are split further, up to
  /// kRefineLevels levels below the stored ones, their support points read (the first split
  /// grid: splitSupport) or evaluated on the spot (the deeper two; none are kept). False as
  /// soon as a cell of the last level still fails beyond `target`, a split cell's own centre is
  /// a direction beyond `target` where F < need, or `budget` (the support points it may still
  /// evaluate, decremented) runs out.
  bool capWithin(const Cap& cap, const Vector3<S>& y, const Vector3<S>& n_star, S need, S target,
                 int* budget) const;
  static constexpr int kRefineLevels = 3;

  /// The stored support point of cell (i, j) of the first grid below the finest level (2 ×
  /// kFinestSide cells per side) on the cube face where component `face` is 1: the point of
  /// the shape that capWithin reads for that cell in place of an evaluation (a little inside
  /// the surface; the constructor).
  Vector3<S> splitSupport(int face, int i, int j) const;
  /// The support points one query may evaluate in capWithin, over all its answers: a check that
  /// holds takes a median of 5–8 of them (docs/math.md → "Splitting cells on the spot"); one
  /// that needs many more is mostly one that fails late, where F stays within a hair of `need`
  /// over a wide set of directions (beside a flat face's sharp rim), and the query's next
  /// answer usually lies there too.
  static constexpr int kSplitSupportPoints = 64;

  /// One level's cells, field by field (the loops over them vectorise). Cell p of a level has
  /// its four children at 4p … 4p + 3 on the next; the coarsest level's cell (face, i, j) is
  /// at (face·kCoarse + i)·kCoarse + j. The geometry, the same for every shape.
  struct LevelGeometry {
    std::vector<S> ax, ay, az;       // unit centre direction a
    std::vector<S> cos_t;            // cosine of the cell's half-angle θ about a (rounded down)
    std::vector<S> sin2_t;           // sin²θ (rounded up)
    std::vector<S> chord;            // ‖n − a‖ ≤ chord for every n of the cell (rounded up)
    std::vector<std::uint8_t> face;  // the cube face the cell lies on
  };

 private:
  /// The shape's support points of one level's cells, evaluated a group at a time (ready_).
  struct LevelSupport {
    std::vector<S> sx, sy, sz;  // support point s in direction a, a few ulps inside the shape
    std::vector<S> h;           // a·s, so F(a) = h − a·y
    std::vector<S> ss;          // ‖s‖², so ‖s − y‖² = ss − 2·s·y + ‖y‖²
  };

  /// The finest level's failing cells for (y, need), written to `failing` (room for every
  /// finest cell); returns their number.
  std::size_t failingFinest(const Vector3<S>& y, S need, std::uint16_t* failing) const;

  /// Groups whose support points are evaluated together, each with its flag in ready_: the
  /// coarsest level (one group), the four children of each cell of the levels above the finest,
  /// and the four first-split-grid cells inside each finest cell.
  static constexpr std::size_t kLevelGroups[kLevels] = {1, 3 * kCoarse* kCoarse,
                                                        3 * 4 * kCoarse* kCoarse};
  /// The first split-grid group's flag: after every level's.
  static constexpr std::size_t kSplitGroups = kLevelGroups[0] + kLevelGroups[1] + kLevelGroups[2];
  static constexpr std::size_t kGroups = kSplitGroups + kFinestCells;
  static_assert(kLevels == 3, "kLevelGroups lists three levels");
  /// Makes sure the support points of level `level`'s children of cell `parent` (level 0: every
  /// cell, parent ignored) are evaluated.
  void ensureLevel(int level, std::size_t parent) const;
  /// The same for the first split grid's four cells inside finest cell p.
  void ensureSplit(std::size_t p) const;
  /// Runs `fill` once for group `group` (the first caller; the others wait for it).
  template <typename Fill>
  void once(std::size_t group, const Fill& fill) const;

  const std::array<LevelGeometry, kLevels>& geometry_;  // coverGeometry(), per process
  NestedNorm<S> support_;                               // the shape's support function
  S size_;                                              // the shape's size (its largest radius)
  mutable std::array<LevelSupport, kLevels> levels_;
  /// The support points of the first grid below the finest stored level (2·kFinestSide cells
  /// per face side, 3,072 in all), which capWithin would otherwise evaluate most often: x, y, z
  /// per cell, face by face, row-major, in units of size_ and pulled inward (ensureSplit), in
  /// float (37 KB).
  mutable std::vector<float> split_support_;
  /// Per group: 0 not evaluated, 1 being evaluated, 2 evaluated.
  std::unique_ptr<std::atomic<std::uint8_t>[]> ready_;
};

extern template class DirectionCover<float>;
extern template class DirectionCover<double>;

/// The shape's direction cover, built on first use and then kept with the shape
/// (shape/shape_caches.h).
template <typename S>
const DirectionCover<S>& directionCover(const Superellipsoid<S>& shape) {
  return ShapeCaches<S>::of(shape).directionCover(
      [&shape] { return std::make_shared<const DirectionCover<S>>(shape); });
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SOLVERS_DIRECTION_COVER_H
