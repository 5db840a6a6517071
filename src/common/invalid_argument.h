#ifndef FCL_SUPERELLIPSOID_SRC_COMMON_INVALID_ARGUMENT_H
#define FCL_SUPERELLIPSOID_SRC_COMMON_INVALID_ARGUMENT_H

// Internal: the one way the library reports bad input. Every public entry point that refuses
// a value throws std::invalid_argument with the message
//
//     "<where>: <requirement>, got <value>"
//
// e.g. "pointDistance: options.tolerance must be finite and > 0, got -0.001". Scalars are
// printed with enough digits to round-trip (max_digits10 of their type), so the value in the
// message is the value the caller passed; vectors as "(x, y, z)". The catalogue of what each
// entry point refuses is docs/hardening.md → "Bad input".

#include <Eigen/Core>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace fcl_superellipsoid {
namespace detail {

/// Writes a scalar with max_digits10 digits of its own type (integers as they are), an Eigen
/// vector as (x, y, z) with its components written the same way.
template <typename T>
void writeValue(std::ostream& out, const T& value) {
  if constexpr (std::is_base_of<Eigen::EigenBase<T>, T>::value) {
    out << "(";
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      if (i > 0) out << ", ";
      writeValue(out, value(i));
    }
    out << ")";
  } else if constexpr (std::is_floating_point<T>::value) {
    out << std::setprecision(std::numeric_limits<T>::max_digits10) << value;
  } else {
    out << value;
  }
}

/// A limit written into a requirement ("must be in [1e-50, 1e+50]"): six significant digits,
/// enough for the round limits the library states.
template <typename T>
std::string formatValue(const T& value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Throws std::invalid_argument("<where>: <requirement>, got <value>").
template <typename T>
[[noreturn]] void throwInvalidArgument(const std::string& where, const std::string& requirement,
                                       const T& value) {
  std::ostringstream msg;
  msg << where << ": " << requirement << ", got ";
  writeValue(msg, value);
  throw std::invalid_argument(msg.str());
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_COMMON_INVALID_ARGUMENT_H
