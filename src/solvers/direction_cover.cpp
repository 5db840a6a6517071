#include "solvers/direction_cover.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <thread>
#include <utility>

namespace fcl_superellipsoid {
namespace detail {

namespace {

/// One cell (i, j) of the k × k grid on the cube face where component `face` is 1: its unit
/// centre direction a and its half-angle θ about a, computed in double and rounded outward into
/// S (the cosine down, sine and chord up).
template <typename S>
struct Cell {
  Vector3<S> a;
  S cos_t, sin2_t, chord;
};

template <typename S>
Cell<S> cellGeometry(int face, int i, int j, int k) {
  const double slack = 16 * double(std::numeric_limits<S>::epsilon());
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
  return {a.cast<S>(), S(cos_t - slack), S(std::max(0.0, 1 - cos_t * cos_t) + slack),
          S(std::sqrt(2 * (1 - cos_t)) + slack)};
}

/// The cells of the grids split below the stored finest one (DirectionCover::capWithin) on the
/// face where component 0 is 1: grid r (0 … refine − 1) is (finest·2^(r+1))², cell (i, j) at
/// i·k + j. They do not depend on the shape: built once per process, on first use (21,504
/// cells, about 1 MB in double; docs/math.md → "Splitting cells on the spot").
template <typename S, int finest, int refine>
const std::array<std::vector<Cell<S>>, refine>& splitGrids() {
  static const std::array<std::vector<Cell<S>>, refine> grids = [] {
    std::array<std::vector<Cell<S>>, refine> out;
    for (int r = 0; r < refine; ++r) {
      const int k = finest << (r + 1);
      out[r].reserve(std::size_t(k) * k);
      for (int i = 0; i < k; ++i) {
        for (int j = 0; j < k; ++j) out[r].push_back(cellGeometry<S>(0, i, j, k));
      }
    }
    return out;
  }();
  return grids;
}

/// A face-0 cell's direction moved to `face` (cellGeometry's direction: component `face` is 1,
/// the next two cyclically are u and v); its angles stay.
template <typename S>
Vector3<S> onFace(const Vector3<S>& a0, int face) {
  Vector3<S> a;
  a[face] = a0[0];
  a[(face + 1) % 3] = a0[1];
  a[(face + 2) % 3] = a0[2];
  return a;
}

/// The support point of a cell's centre direction a (largest component a[face]: ∇h is
/// 0-homogeneous, as in Superellipsoid::supportPoint), pulled a few ulps toward the centre so
/// that it lies inside the shape despite rounding (the bounds need points of the shape, not
/// near it).
template <typename S>
Vector3<S> supportInside(const NestedNorm<S>& support, const Vector3<S>& a, int face) {
  const S inward = S(1) - S(64) * std::numeric_limits<S>::epsilon();
  return inward * support.gradient(a / a[face]);
}

/// A cell passes if its lower bound of F = h − n·y over the cell reaches `need`: with w = s − y,
/// min over the cell of n·w ≥ ‖w‖·cos(φ + θ) = (a·w)·cos θ − ‖w‖·sin φ·sin θ, compared squared
/// (no square root): A = (a·w)·cos θ − need ≥ 0 and A² ≥ (‖w‖² − (a·w)²)·sin²θ. Takes
/// a·w = a·s − a·y (`along`), s·y, ‖s‖² and ‖y‖².
template <typename S>
inline bool boundReaches(S along, S sy, S ss, S yy, S cos_t, S sin2_t, S need) {
  const S margin = along * cos_t - need;
  const S across_squared = std::max(S(0), ss - S(2) * sy + yy - along * along);
  return (margin >= S(0)) & (margin * margin >= across_squared * sin2_t);  // no branch
}

/// The finest level's cell p as (face, i, j) of its face's kFinestSide × kFinestSide grid: the
/// coarse cell (face·kCoarse + i)·kCoarse + j, then per level the child 2·di + dj, from the
/// coarsest level's digits down.
template <int kCoarse, int kLevels>
void finestCell(std::size_t p, int* face, int* i, int* j) {
  std::size_t rest = p;
  *i = 0;
  *j = 0;
  for (int level = kLevels - 1, bit = 0; level > 0; --level, ++bit) {
    const int child = int(rest % 4);
    rest /= 4;
    *i |= (child / 2) << bit;
    *j |= (child % 2) << bit;
  }
  *face = int(rest / (kCoarse * kCoarse));
  *i += int(rest / kCoarse % kCoarse) << (kLevels - 1);
  *j += int(rest % kCoarse) << (kLevels - 1);
}

/// The inverse: the finest cell (face, i, j) as its index p.
template <int kCoarse, int kLevels>
std::size_t finestIndex(int face, int i, int j) {
  std::size_t p = (std::size_t(face) * kCoarse + std::size_t(i >> (kLevels - 1))) * kCoarse +
                  std::size_t(j >> (kLevels - 1));
  for (int bit = kLevels - 2; bit >= 0; --bit) {
    p = 4 * p + std::size_t(2 * ((i >> bit) & 1) + ((j >> bit) & 1));
  }
  return p;
}

/// The cells' geometry on every level (the same for every shape), built once per process.
template <typename S, int kCoarse, int kLevels>
const std::array<typename DirectionCover<S>::LevelGeometry, kLevels>& coverGeometry() {
  using LevelGeometry = typename DirectionCover<S>::LevelGeometry;
  static const std::array<LevelGeometry, kLevels> levels = [] {
    struct Square {
      int face, i, j;  // cell (i, j) of the face's k × k grid
    };
    std::vector<Square> squares;
    for (int face = 0; face < 3; ++face) {
      for (int i = 0; i < kCoarse; ++i) {
        for (int j = 0; j < kCoarse; ++j) squares.push_back({face, i, j});
      }
    }
    std::array<LevelGeometry, kLevels> out;
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
      LevelGeometry& cells = out[level];
      for (const Square& q : squares) {
        const Cell<S> c = cellGeometry<S>(q.face, q.i, q.j, k);
        cells.ax.push_back(c.a[0]);
        cells.ay.push_back(c.a[1]);
        cells.az.push_back(c.a[2]);
        cells.cos_t.push_back(c.cos_t);
        cells.sin2_t.push_back(c.sin2_t);
        cells.chord.push_back(c.chord);
        cells.face.push_back(static_cast<std::uint8_t>(q.face));
      }
    }
    return out;
  }();
  return levels;
}

}  // namespace

template <typename S>
DirectionCover<S>::DirectionCover(const Superellipsoid<S>& shape)
    : geometry_(coverGeometry<S, kCoarse, kLevels>()),
      support_(NestedNorm<S>::support(shape)),
      size_(shape.size()),
      ready_(new std::atomic<std::uint8_t>[kGroups]) {
  for (int level = 0; level < kLevels; ++level) {
    const std::size_t n = geometry_[level].ax.size();
    for (std::vector<S>* field : {&levels_[level].sx, &levels_[level].sy, &levels_[level].sz,
                                  &levels_[level].h, &levels_[level].ss}) {
      field->resize(n);
    }
  }
  split_support_.resize(3 * 4 * kFinestCells);
  for (std::size_t g = 0; g < kGroups; ++g) ready_[g].store(0, std::memory_order_relaxed);
}

template <typename S>
template <typename Fill>
void DirectionCover<S>::once(std::size_t group, const Fill& fill) const {
  std::atomic<std::uint8_t>& flag = ready_[group];
  if (flag.load(std::memory_order_acquire) == 2) return;
  std::uint8_t empty = 0;
  if (flag.compare_exchange_strong(empty, 1, std::memory_order_acquire)) {
    fill();
    flag.store(2, std::memory_order_release);
    return;
  }
  // Another thread is evaluating it: four support points.
  while (flag.load(std::memory_order_acquire) != 2) std::this_thread::yield();
}

template <typename S>
void DirectionCover<S>::ensureLevel(int level, std::size_t parent) const {
  std::size_t group = 0, first = 0, count = geometry_[0].ax.size();
  if (level > 0) {
    group = parent;
    for (int l = 0; l < level; ++l) group += kLevelGroups[l];
    first = 4 * parent;
    count = 4;
  }
  once(group, [&] {
    const LevelGeometry& g = geometry_[level];
    LevelSupport& cells = levels_[level];
    for (std::size_t p = first; p < first + count; ++p) {
      const Vector3<S> a(g.ax[p], g.ay[p], g.az[p]);
      const Vector3<S> support = supportInside(support_, a, g.face[p]);
      cells.sx[p] = support[0];
      cells.sy[p] = support[1];
      cells.sz[p] = support[2];
      cells.h[p] = a.dot(support);
      cells.ss[p] = support.squaredNorm();
    }
  });
}

template <typename S>
void DirectionCover<S>::ensureSplit(std::size_t p) const {
  once(kSplitGroups + p, [&] {
    // The first split grid's support points, relative to the size and pulled inward by 2^-20:
    // G is 1-homogeneous and grows with each coordinate in the octant, so the roundings on the
    // way (to float and back, a few ulps of float at most) leave the point inside the shape.
    const auto& grid = splitGrids<S, kFinestSide, kRefineLevels>()[0];
    constexpr int kSide = 2 * kFinestSide;
    const S inward = (S(1) - S(1.0 / (1 << 20))) / size_;
    int face = 0, i = 0, j = 0;
    finestCell<kCoarse, kLevels>(p, &face, &i, &j);
    for (int di = 0; di < 2; ++di) {
      for (int dj = 0; dj < 2; ++dj) {
        const std::size_t c = std::size_t(2 * i + di) * kSide + std::size_t(2 * j + dj);
        const Vector3<S> s = inward * supportInside(support_, onFace(grid[c].a, face), face);
        for (int k = 0; k < 3; ++k) {
          split_support_[3 * (std::size_t(face) * grid.size() + c) + k] = float(s[k]);
        }
      }
    }
  });
}

template <typename S>
Vector3<S> DirectionCover<S>::splitSupport(int face, int i, int j) const {
  constexpr std::size_t kSide = 2 * kFinestSide;
  ensureSplit(finestIndex<kCoarse, kLevels>(face, i / 2, j / 2));
  const float* stored = &split_support_[3 * ((std::size_t(face) * kSide + i) * kSide + j)];
  return Vector3<S>(S(stored[0]), S(stored[1]), S(stored[2])) * size_;
}

template <typename S>
Vector3<S> DirectionCover<S>::startNear(const Vector3<S>& y) const {
  // F(a) = h − a·y, smallest among the coarse cells, then among each chosen cell's children.
  auto value = [&](int level, std::size_t p) {
    const LevelGeometry& g = geometry_[level];
    return levels_[level].h[p] - (g.ax[p] * y[0] + g.ay[p] * y[1] + g.az[p] * y[2]);
  };
  ensureLevel(0, 0);
  std::size_t best = 0;
  S lowest = value(0, 0);
  for (std::size_t p = 1; p < geometry_[0].ax.size(); ++p) {
    const S v = value(0, p);
    if (v < lowest) {
      lowest = v;
      best = p;
    }
  }
  for (int level = 1; level < kLevels; ++level) {
    ensureLevel(level, best);
    const std::size_t first = 4 * best;
    best = first;
    lowest = value(level, first);
    for (std::size_t p = first + 1; p < first + 4; ++p) {
      const S v = value(level, p);
      if (v < lowest) {
        lowest = v;
        best = p;
      }
    }
  }
  const LevelSupport& finest = levels_[kLevels - 1];
  return Vector3<S>(finest.sx[best], finest.sy[best], finest.sz[best]);
}

template <typename S>
std::size_t DirectionCover<S>::failingFinest(const Vector3<S>& y, S need,
                                             std::uint16_t* failing) const {
  const S yy = y.squaredNorm();
  auto passes = [&](int level, std::size_t p) {
    const LevelGeometry& g = geometry_[level];
    const LevelSupport& l = levels_[level];
    const S ay = g.ax[p] * y[0] + g.ay[p] * y[1] + g.az[p] * y[2];
    const S sy = l.sx[p] * y[0] + l.sy[p] * y[1] + l.sz[p] * y[2];
    return boundReaches(l.h[p] - ay, sy, l.ss[p], yy, g.cos_t[p], g.sin2_t[p], need);
  };
  // Level by level: the failing cells of one level, then their children on the next. The lists
  // live on the stack (at most the finest level's 768 cells): every inside query that reaches
  // the cover comes here, and two heap lists per call would be a visible part of its time.
  std::array<std::uint16_t, kFinestCells> spare;
  std::uint16_t* next = spare.data();
  std::size_t failing_count = 0;
  // Each cell's index is written and the count advanced only if it fails: no branch on the
  // outcome, which the cells' order does not make predictable.
  ensureLevel(0, 0);
  for (std::size_t p = 0; p < geometry_[0].ax.size(); ++p) {
    failing[failing_count] = static_cast<std::uint16_t>(p);
    failing_count += !passes(0, p);
  }
  for (int level = 1; level < kLevels; ++level) {
    std::size_t next_count = 0;
    for (std::size_t k = 0; k < failing_count; ++k) {
      ensureLevel(level, failing[k]);
      const std::size_t first = 4 * std::size_t(failing[k]);
      for (std::size_t p = first; p < first + 4; ++p) {
        next[next_count] = static_cast<std::uint16_t>(p);
        next_count += !passes(level, p);
      }
    }
    std::copy(next, next + next_count, failing);
    failing_count = next_count;
  }
  return failing_count;
}

template <typename S>
typename DirectionCover<S>::Cap DirectionCover<S>::cap(const Vector3<S>& y,
                                                       const Vector3<S>& n_star, S need,
                                                       S limit) const {
  Cap out;
  out.radius = std::numeric_limits<S>::infinity();
  out.count = 0;
  if (!(y.allFinite() && n_star.allFinite() && std::isfinite(need))) return out;
  out.count = failingFinest(y, need, out.failing.data());
  const LevelGeometry& finest = geometry_[kLevels - 1];
  S radius = S(0);
  for (std::size_t k = 0; k < out.count; ++k) {
    const std::size_t p = out.failing[k];
    const Vector3<S> a(finest.ax[p], finest.ay[p], finest.az[p]);
    radius = std::max(radius, (a - n_star).norm() + finest.chord[p]);
    if (radius > limit) return out;
  }
  out.radius = radius;
  return out;
}

template <typename S>
bool DirectionCover<S>::capWithin(const Cap& cap, const Vector3<S>& y, const Vector3<S>& n_star,
                                  S need, S target, int* budget) const {
  if (!(std::isfinite(cap.radius) && target >= S(0))) return false;
  const S yy = y.squaredNorm();
  // Whether the bound with the point s of the shape reaches `need` over cell c.
  auto passes = [&](const Vector3<S>& a, const Cell<S>& c, const Vector3<S>& s) {
    return boundReaches(a.dot(s) - a.dot(y), s.dot(y), s.squaredNorm(), yy, c.cos_t, c.sin2_t,
                        need);
  };
  // Whether every direction of a cell (direction a, chord c) lies within `target` of n_star:
  // ‖a − n_star‖ + c ≤ target, compared squared (no square root; the slab's 2.01 covers the
  // rounding, as it covers the chord's).
  auto inside_target = [&](const Vector3<S>& a, S chord) {
    const S room = target - chord;
    return room >= S(0) && (a - n_star).squaredNorm() <= room * room;
  };
  // A direction a beyond `target` whose own F, with s its support point (a few ulps inside),
  // is below `need`: the claim is false, and no split can make it true.
  auto refutes = [&](const Vector3<S>& a, const Vector3<S>& s) {
    return a.dot(s) - a.dot(y) < need && (a - n_star).squaredNorm() > target * target;
  };
  // A failing cell (face, i, j) of a k × k grid that reaches beyond `target`, with its support
  // point s: split into its four children of the 2k × 2k grid, `levels` more times at most.
  // A child is first tried with its parent's support point (any point of the shape bounds h
  // from below; a child far from n* often passes with it), and only then with its own.
  const auto& grids = splitGrids<S, kFinestSide, kRefineLevels>();
  auto within = [&](auto& self, int face, int i, int j, int k, int levels,
                    const Vector3<S>& s) -> bool {
    if (levels == 0) return false;
    const int r = kRefineLevels - levels;
    for (int di = 0; di < 2; ++di) {
      for (int dj = 0; dj < 2; ++dj) {
        const int ci = 2 * i + di, cj = 2 * j + dj;
        const Cell<S>& c = grids[r][std::size_t(ci) * (2 * k) + cj];
        const Vector3<S> a = onFace(c.a, face);
        if (inside_target(a, c.chord) || passes(a, c, s)) continue;
        // The first split grid's support points are stored; the deeper ones are evaluated
        // here, within the query's budget.
        Vector3<S> own;
        if (r == 0) {
          own = splitSupport(face, ci, cj);
        } else {
          if (*budget <= 0) return false;
          --*budget;
          own = supportInside(support_, a, face);
        }
        if (passes(a, c, own)) continue;
        if (refutes(a, own)) return false;
        if (!self(self, face, ci, cj, 2 * k, levels - 1, own)) return false;
      }
    }
    return true;
  };
  const LevelGeometry& finest = geometry_[kLevels - 1];
  const LevelSupport& finest_support = levels_[kLevels - 1];  // (cap's cells: evaluated)
  // The cells reaching beyond `target`, nearest first: they are the likeliest to fail.
  struct Beyond {  // trivial, so the array is not zeroed on every call
    S reach;
    std::uint16_t cell;
  };
  std::array<Beyond, kFinestCells> beyond;
  std::size_t beyond_count = 0;
  for (std::size_t k = 0; k < cap.count; ++k) {
    const std::size_t p = cap.failing[k];
    const Vector3<S> a(finest.ax[p], finest.ay[p], finest.az[p]);
    const S reach = (a - n_star).norm() + finest.chord[p];
    if (reach > target) beyond[beyond_count++] = {reach, cap.failing[k]};
  }
  std::sort(beyond.begin(), beyond.begin() + beyond_count,
            [](const Beyond& l, const Beyond& r) { return l.reach < r.reach; });
  for (std::size_t k = 0; k < beyond_count; ++k) {
    const std::size_t p = beyond[k].cell;
    const Vector3<S> a(finest.ax[p], finest.ay[p], finest.az[p]);
    const Vector3<S> s(finest_support.sx[p], finest_support.sy[p], finest_support.sz[p]);
    if (refutes(a, s)) return false;
    int face = 0, i = 0, j = 0;
    finestCell<kCoarse, kLevels>(p, &face, &i, &j);
    if (!within(within, face, i, j, kFinestSide, kRefineLevels, s)) return false;
  }
  return true;
}

template class DirectionCover<float>;
template class DirectionCover<double>;

}  // namespace detail
}  // namespace fcl_superellipsoid
