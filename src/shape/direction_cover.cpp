#include "shape/direction_cover.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
void DirectionCover<S>::Level::resize(std::size_t n) {
  for (std::vector<S>* field : {&ax, &ay, &az, &sx, &sy, &sz, &h, &ss, &cos_t, &sin2_t, &chord}) {
    field->resize(n);
  }
}

namespace {

/// One cell (i, j) of the k × k grid on the cube face where component `face` is 1: its unit
/// centre direction a, the support point s there (pulled a few ulps toward the centre, so that
/// it lies inside the shape despite rounding: the bounds need points of the shape, not near it),
/// and its half-angle θ about a, the geometry in double, rounded outward into S (the cosine
/// down, sine and chord up).
template <typename S>
struct Cell {
  Vector3<S> a, s;
  S cos_t, sin2_t, chord;
};

template <typename S>
Cell<S> makeCell(const NestedNorm<S>& support, int face, int i, int j, int k) {
  const double slack = 16 * double(std::numeric_limits<S>::epsilon());
  const S inward = S(1) - S(64) * std::numeric_limits<S>::epsilon();
  // The direction through the point (u, v) of the face.
  auto direction = [face](double u, double v) {
    Eigen::Vector3d d;
    d[face] = 1;
    d[(face + 1) % 3] = u;
    d[(face + 2) % 3] = v;
    return Eigen::Vector3d(d.normalized());
  };
  const Eigen::Vector3d a = direction((i + 0.5) / k, (j + 0.5) / k);
  // The angle from a is quasi-convex over the face's plane (its sublevel sets are the plane's
  // sections of circular cones about a), so over the square it is largest at a corner.
  double cos_t = 1;
  for (int ci = 0; ci < 2; ++ci) {
    for (int cj = 0; cj < 2; ++cj) {
      cos_t = std::min(cos_t, a.dot(direction(double(i + ci) / k, double(j + cj) / k)));
    }
  }
  Cell<S> cell;
  cell.a = a.cast<S>();
  // ∇h is 0-homogeneous: the largest component of a is its face's (Superellipsoid::supportPoint).
  cell.s = inward * support.gradient(cell.a / cell.a[face]);
  cell.cos_t = S(cos_t - slack);
  cell.sin2_t = S(std::max(0.0, 1 - cos_t * cos_t) + slack);
  cell.chord = S(std::sqrt(2 * (1 - cos_t)) + slack);
  return cell;
}

/// A cell passes if its lower bound of F = h − n·y over the cell reaches `need`: with w = s − y,
/// min over the cell of n·w ≥ ‖w‖·cos(φ + θ) = (a·w)·cos θ − ‖w‖·sin φ·sin θ, compared squared
/// (no square root): A = (a·w)·cos θ − need ≥ 0 and A² ≥ (‖w‖² − (a·w)²)·sin²θ. Takes
/// a·w = a·s − a·y (`along`), s·y, ‖s‖² and ‖y‖².
template <typename S>
inline bool boundReaches(S along, S sy, S ss, S yy, S cos_t, S sin2_t, S need) {
  const S margin = along * cos_t - need;
  const S across_squared = std::max(S(0), ss - S(2) * sy + yy - along * along);
  return margin >= S(0) && margin * margin >= across_squared * sin2_t;
}

}  // namespace

template <typename S>
DirectionCover<S>::DirectionCover(const Superellipsoid<S>& shape)
    : support_(NestedNorm<S>::support(shape)) {
  struct Square {
    int face, i, j;  // cell (i, j) of the face's k × k grid
  };
  std::vector<Square> squares;
  for (int face = 0; face < 3; ++face) {
    for (int i = 0; i < kCoarse; ++i) {
      for (int j = 0; j < kCoarse; ++j) squares.push_back({face, i, j});
    }
  }
  for (int level = 0; level < kLevels; ++level) {
    if (level > 0) {  // children in the order 4p + 2·di + dj
      std::vector<Square> children;
      for (const Square& q : squares) {
        for (int di = 0; di < 2; ++di) {
          for (int dj = 0; dj < 2; ++dj) children.push_back({q.face, 2 * q.i + di, 2 * q.j + dj});
        }
      }
      squares.swap(children);
    }
    const int k = kCoarse << level;
    Level& cells = levels_[level];
    cells.resize(squares.size());
    for (std::size_t p = 0; p < squares.size(); ++p) {
      const Square& q = squares[p];
      const Cell<S> c = makeCell(support_, q.face, q.i, q.j, k);
      cells.ax[p] = c.a[0];
      cells.ay[p] = c.a[1];
      cells.az[p] = c.a[2];
      cells.sx[p] = c.s[0];
      cells.sy[p] = c.s[1];
      cells.sz[p] = c.s[2];
      cells.h[p] = c.a.dot(c.s);
      cells.ss[p] = c.s.squaredNorm();
      cells.cos_t[p] = c.cos_t;
      cells.sin2_t[p] = c.sin2_t;
      cells.chord[p] = c.chord;
    }
  }
}

template <typename S>
Vector3<S> DirectionCover<S>::startNear(const Vector3<S>& y) const {
  // F(a) = h − a·y, smallest among the coarse cells, then among each chosen cell's children.
  auto value = [&y](const Level& l, std::size_t p) {
    return l.h[p] - (l.ax[p] * y[0] + l.ay[p] * y[1] + l.az[p] * y[2]);
  };
  std::size_t best = 0;
  S lowest = value(levels_[0], 0);
  for (std::size_t p = 1; p < levels_[0].h.size(); ++p) {
    const S v = value(levels_[0], p);
    if (v < lowest) {
      lowest = v;
      best = p;
    }
  }
  for (int level = 1; level < kLevels; ++level) {
    const std::size_t first = 4 * best;
    best = first;
    lowest = value(levels_[level], first);
    for (std::size_t p = first + 1; p < first + 4; ++p) {
      const S v = value(levels_[level], p);
      if (v < lowest) {
        lowest = v;
        best = p;
      }
    }
  }
  const Level& finest = levels_[kLevels - 1];
  return Vector3<S>(finest.sx[best], finest.sy[best], finest.sz[best]);
}

template <typename S>
std::size_t DirectionCover<S>::failingFinest(const Vector3<S>& y, S need,
                                             std::uint16_t* failing) const {
  const S yy = y.squaredNorm();
  auto passes = [&](const Level& l, std::size_t p) {
    const S ay = l.ax[p] * y[0] + l.ay[p] * y[1] + l.az[p] * y[2];
    const S sy = l.sx[p] * y[0] + l.sy[p] * y[1] + l.sz[p] * y[2];
    return boundReaches(l.h[p] - ay, sy, l.ss[p], yy, l.cos_t[p], l.sin2_t[p], need);
  };
  // Level by level: the failing cells of one level, then their children on the next. The lists
  // live on the stack (at most the finest level's 768 cells): two heap lists per call cost the
  // uniform inside queries 2–4 % of their time.
  std::array<std::uint16_t, kFinestCells> spare;
  std::uint16_t* next = spare.data();
  std::size_t failing_count = 0;
  for (std::size_t p = 0; p < levels_[0].h.size(); ++p) {
    if (!passes(levels_[0], p)) failing[failing_count++] = static_cast<std::uint16_t>(p);
  }
  for (int level = 1; level < kLevels; ++level) {
    std::size_t next_count = 0;
    const Level& cells = levels_[level];
    for (std::size_t k = 0; k < failing_count; ++k) {
      const std::size_t first = 4 * std::size_t(failing[k]);
      for (std::size_t p = first; p < first + 4; ++p) {
        if (!passes(cells, p)) next[next_count++] = static_cast<std::uint16_t>(p);
      }
    }
    std::copy(next, next + next_count, failing);
    failing_count = next_count;
  }
  return failing_count;
}

template <typename S>
S DirectionCover<S>::capRadius(const Vector3<S>& y, const Vector3<S>& n_star, S need,
                               S limit) const {
  const S beyond = std::numeric_limits<S>::infinity();
  if (!(y.allFinite() && n_star.allFinite() && std::isfinite(need))) return beyond;
  std::array<std::uint16_t, kFinestCells> failing;
  const std::size_t count = failingFinest(y, need, failing.data());
  const Level& finest = levels_[kLevels - 1];
  S radius = S(0);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t p = failing[k];
    const Vector3<S> a(finest.ax[p], finest.ay[p], finest.az[p]);
    radius = std::max(radius, (a - n_star).norm() + finest.chord[p]);
    if (radius > limit) return beyond;
  }
  return radius;
}

template <typename S>
bool DirectionCover<S>::capWithin(const Vector3<S>& y, const Vector3<S>& n_star, S need,
                                  S target) const {
  if (!(y.allFinite() && n_star.allFinite() && std::isfinite(need) && target >= S(0))) {
    return false;
  }
  const S yy = y.squaredNorm();
  // A failing cell (face, i, j) of a k × k grid that reaches beyond `target`: split into its
  // four children of the 2k × 2k grid, `levels` more times at most.
  auto within = [&](auto& self, int face, int i, int j, int k, int levels) -> bool {
    if (levels == 0) return false;
    for (int di = 0; di < 2; ++di) {
      for (int dj = 0; dj < 2; ++dj) {
        const Cell<S> c = makeCell(support_, face, 2 * i + di, 2 * j + dj, 2 * k);
        const S along = c.a.dot(c.s) - c.a.dot(y);
        if (boundReaches(along, c.s.dot(y), c.s.squaredNorm(), yy, c.cos_t, c.sin2_t, need)) {
          continue;
        }
        if ((c.a - n_star).norm() + c.chord <= target) continue;
        if (!self(self, face, 2 * i + di, 2 * j + dj, 2 * k, levels - 1)) return false;
      }
    }
    return true;
  };
  std::array<std::uint16_t, kFinestCells> failing;
  const std::size_t count = failingFinest(y, need, failing.data());
  const Level& finest = levels_[kLevels - 1];
  // The cells reaching beyond `target`, nearest first: they are the likeliest to fail.
  std::array<std::pair<S, std::uint16_t>, kFinestCells> beyond;
  std::size_t beyond_count = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t p = failing[k];
    const Vector3<S> a(finest.ax[p], finest.ay[p], finest.az[p]);
    const S reach = (a - n_star).norm() + finest.chord[p];
    if (reach > target) beyond[beyond_count++] = {reach, failing[k]};
  }
  std::sort(beyond.begin(), beyond.begin() + beyond_count,
            [](const auto& l, const auto& r) { return l.first < r.first; });
  constexpr int kFinest = kCoarse << (kLevels - 1);
  for (std::size_t k = 0; k < beyond_count; ++k) {
    const std::size_t p = beyond[k].second;
    // Its (face, i, j): the coarse cell (face·kCoarse + i)·kCoarse + j, then per level the child
    // 2·di + dj, from the coarsest level's digits down.
    std::size_t rest = p;
    int i = 0, j = 0;
    for (int level = kLevels - 1, bit = 0; level > 0; --level, ++bit) {
      const int child = int(rest % 4);
      rest /= 4;
      i |= (child / 2) << bit;
      j |= (child % 2) << bit;
    }
    const int face = int(rest / (kCoarse * kCoarse));
    i += int(rest / kCoarse % kCoarse) << (kLevels - 1);
    j += int(rest % kCoarse) << (kLevels - 1);
    if (!within(within, face, i, j, kFinest, kRefineLevels)) return false;
  }
  return true;
}

template class DirectionCover<float>;
template class DirectionCover<double>;

}  // namespace detail
}  // namespace fcl_superellipsoid
