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

template <typename S>
DirectionCover<S>::DirectionCover(const Superellipsoid<S>& shape) {
  // The cells' geometry in double, rounded outward into S: the cosine down, sine and chord up.
  const double slack = 16 * double(std::numeric_limits<S>::epsilon());
  const S inward = S(1) - S(64) * std::numeric_limits<S>::epsilon();
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
      // The direction through the point (u, v) of the cube face where component `face` is 1.
      auto direction = [&q](double u, double v) {
        Eigen::Vector3d d;
        d[q.face] = 1;
        d[(q.face + 1) % 3] = u;
        d[(q.face + 2) % 3] = v;
        return Eigen::Vector3d(d.normalized());
      };
      const Eigen::Vector3d a = direction((q.i + 0.5) / k, (q.j + 0.5) / k);
      // The angle from a is quasi-convex over the face's plane (its sublevel sets are the
      // plane's sections of circular cones about a), so over the square it is largest at a
      // corner.
      double cos_t = 1;
      for (int ci = 0; ci < 2; ++ci) {
        for (int cj = 0; cj < 2; ++cj) {
          cos_t = std::min(cos_t, a.dot(direction(double(q.i + ci) / k, double(q.j + cj) / k)));
        }
      }
      const Vector3<S> a_s = a.cast<S>();
      const Vector3<S> s = inward * shape.supportPoint(a_s);
      cells.ax[p] = a_s[0];
      cells.ay[p] = a_s[1];
      cells.az[p] = a_s[2];
      cells.sx[p] = s[0];
      cells.sy[p] = s[1];
      cells.sz[p] = s[2];
      cells.h[p] = a_s.dot(s);
      cells.ss[p] = s.squaredNorm();
      cells.cos_t[p] = S(cos_t - slack);
      cells.sin2_t[p] = S(std::max(0.0, 1 - cos_t * cos_t) + slack);
      cells.chord[p] = S(std::sqrt(2 * (1 - cos_t)) + slack);
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
S DirectionCover<S>::capRadius(const Vector3<S>& y, const Vector3<S>& n_star, S need,
                               S limit) const {
  const S beyond = std::numeric_limits<S>::infinity();
  if (!(y.allFinite() && n_star.allFinite() && std::isfinite(need))) return beyond;
  const S yy = y.squaredNorm();
  // A cell passes if its lower bound of F over the cell reaches `need`: with w = s − y,
  // min over the cell of n·w ≥ ‖w‖·cos(φ + θ) = (a·w)·cos θ − ‖w‖·sin φ·sin θ, compared squared
  // (no square root): A = (a·w)·cos θ − need ≥ 0 and A² ≥ (‖w‖² − (a·w)²)·sin²θ.
  auto passes = [&](const Level& l, std::size_t p) {
    const S ay = l.ax[p] * y[0] + l.ay[p] * y[1] + l.az[p] * y[2];
    const S sy = l.sx[p] * y[0] + l.sy[p] * y[1] + l.sz[p] * y[2];
    const S along = l.h[p] - ay;
    const S margin = along * l.cos_t[p] - need;
    const S across_squared = std::max(S(0), l.ss[p] - S(2) * sy + yy - along * along);
    return margin >= S(0) && margin * margin >= across_squared * l.sin2_t[p];
  };
  // Level by level: the failing cells of one level, then their children on the next. The lists
  // live on the stack (at most the finest level's 768 cells): two heap lists per call cost the
  // uniform inside queries 2–4 % of their time.
  constexpr std::size_t kFinestCells = 3 * kCoarse * kCoarse << (2 * (kLevels - 1));
  std::array<std::uint16_t, kFinestCells> lists[2];
  std::uint16_t* failing = lists[0].data();
  std::uint16_t* next = lists[1].data();
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
    std::swap(failing, next);
    failing_count = next_count;
  }
  const Level& finest = levels_[kLevels - 1];
  S radius = S(0);
  for (std::size_t k = 0; k < failing_count; ++k) {
    const std::size_t p = failing[k];
    const Vector3<S> a(finest.ax[p], finest.ay[p], finest.az[p]);
    radius = std::max(radius, (a - n_star).norm() + finest.chord[p]);
    if (radius > limit) return beyond;
  }
  return radius;
}

template class DirectionCover<float>;
template class DirectionCover<double>;

}  // namespace detail
}  // namespace fcl_superellipsoid
