#include "arrays.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace fcl_superellipsoid {
namespace python {

namespace {

std::string shapeText(const py::array& array) {
  std::ostringstream text;
  text << "(";
  for (py::ssize_t k = 0; k < array.ndim(); ++k) text << (k ? ", " : "") << array.shape(k);
  text << (array.ndim() == 1 ? ",)" : ")");
  return text.str();
}

std::string dtypeText(const py::array& array) {
  return py::str(static_cast<py::object>(array.dtype())).cast<std::string>();
}

/// `values` as a float64 array (a copy only when it is not one already).
py::array_t<double> doublesOf(const py::handle& values, const char* name) {
  py::array array = py::array::ensure(values);
  if (!array) throw py::type_error(std::string(name) + ": expected an array of numbers");
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::type_error(std::string(name) + ": expected real numbers, got dtype " +
                         dtypeText(array));
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
}

}  // namespace

std::pair<py::array, Precision> pointsArray(const py::handle& points, const char* name) {
  py::array array = py::array::ensure(points);  // an array as it is; anything else through numpy
  if (!array) throw py::type_error(std::string(name) + ": expected an array of points");
  const py::dtype dtype = array.dtype();
  Precision precision = Precision::kDouble;
  if (dtype.is(py::dtype::of<float>())) {
    precision = Precision::kFloat;
  } else if (!dtype.is(py::dtype::of<double>())) {
    const char kind = dtype.kind();
    if (kind != 'i' && kind != 'u') {
      throw py::type_error(std::string(name) +
                           ": expected float32 or float64 (or integer) "
                           "points, got dtype " +
                           dtypeText(array));
    }
    array = py::array_t<double, py::array::forcecast>::ensure(array);
  }
  const bool single = array.ndim() == 1 && array.shape(0) == 3;
  const bool many = array.ndim() == 2 && array.shape(1) == 3;
  if (!single && !many) {
    throw py::value_error(std::string(name) + ": expected shape (N, 3) or (3,), got " +
                          shapeText(array));
  }
  return {array, precision};
}

template <typename S>
PointColumns<S>::PointColumns(const py::array& array) : view_(viewOf(array, copy_, single_)) {}

template <typename S>
typename PointColumns<S>::View PointColumns<S>::viewOf(const py::array& array, Matrix& copy,
                                                       bool& single) {
  single = array.ndim() == 1;
  const Eigen::Index n = single ? 1 : array.shape(0);
  const auto item = static_cast<py::ssize_t>(sizeof(S));
  const py::ssize_t coordinate_stride = single ? array.strides(0) : array.strides(1);
  const py::ssize_t point_stride = single ? 3 * item : array.strides(0);
  const bool aligned = (array.flags() & py::detail::npy_api::NPY_ARRAY_ALIGNED_) != 0;
  const auto* data = static_cast<const S*>(array.data());
  if (aligned && coordinate_stride == item && point_stride >= 3 * item &&
      point_stride % item == 0) {
    return View(data, 3, n, Eigen::OuterStride<>(n > 1 ? point_stride / item : 3));
  }
  // Another layout (a transposed or negatively strided view, unaligned memory): one copy.
  copy.resize(3, n);
  const auto* bytes = static_cast<const char*>(array.data());
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      S value;
      std::memcpy(&value, bytes + i * point_stride + k * coordinate_stride, sizeof(S));
      copy(k, i) = value;
    }
  }
  return View(copy.data(), 3, n, Eigen::OuterStride<>(3));
}

fcl::Transform3<double> poseOf(const py::handle& pose, const char* name) {
  fcl::Transform3<double> X = fcl::Transform3<double>::Identity();
  if (pose.is_none()) return X;
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  const bool pair =
      (py::isinstance<py::tuple>(pose) || py::isinstance<py::list>(pose)) && py::len(pose) == 2;
  if (pair) {
    py::array_t<double> r = doublesOf(py::reinterpret_borrow<py::sequence>(pose)[0], name);
    py::array_t<double> p = doublesOf(py::reinterpret_borrow<py::sequence>(pose)[1], name);
    if (r.ndim() != 2 || r.shape(0) != 3 || r.shape(1) != 3 || p.size() != 3 || p.ndim() != 1) {
      throw py::value_error(std::string(name) +
                            ": expected (R, t) with R of shape (3, 3) and t "
                            "of shape (3,), got R " +
                            shapeText(r) + " and t " + shapeText(p));
    }
    for (int i = 0; i < 3; ++i) {
      t(i) = p.at(i);
      for (int j = 0; j < 3; ++j) R(i, j) = r.at(i, j);
    }
  } else {
    py::array_t<double> m = doublesOf(pose, name);
    if (m.ndim() != 2 || m.shape(0) != 4 || m.shape(1) != 4) {
      throw py::value_error(std::string(name) +
                            ": expected None, a (4, 4) matrix or a pair "
                            "(R, t), got shape " +
                            shapeText(m));
    }
    for (int i = 0; i < 3; ++i) {
      t(i) = m.at(i, 3);
      for (int j = 0; j < 3; ++j) R(i, j) = m.at(i, j);
    }
    for (int j = 0; j < 4; ++j) {
      if (m.at(3, j) != (j == 3 ? 1.0 : 0.0)) {
        std::ostringstream text;
        text << name << ": the last row of a pose must be (0, 0, 0, 1), got (" << m.at(3, 0) << ", "
             << m.at(3, 1) << ", " << m.at(3, 2) << ", " << m.at(3, 3) << ")";
        throw py::value_error(text.str());
      }
    }
  }
  if (!R.allFinite() || !t.allFinite()) {
    std::ostringstream text;
    text << name << ": a pose must be finite, got R = ["
         << R.format(Eigen::IOFormat(6, 0, ", ", "; ")) << "], t = ("
         << t.transpose().format(Eigen::IOFormat(6, 0, ", ")) << ")";
    throw py::value_error(text.str());
  }
  const double orthogonality =
      (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = R.determinant();
  if (!(orthogonality <= 1e-6) || !(std::abs(det - 1.0) <= 1e-6)) {
    std::ostringstream text;
    text << name << ": R is not a rotation (max |RᵀR − I| = " << orthogonality
         << ", det R = " << det << ")";
    throw py::value_error(text.str());
  }
  X.linear() = R;
  X.translation() = t;
  return X;
}

Eigen::VectorXd finiteVector(const py::handle& values, Eigen::Index n, const char* name) {
  py::array_t<double> array = doublesOf(values, name);
  if (array.ndim() != 1 || array.shape(0) != n) {
    throw py::value_error(std::string(name) + ": expected " + std::to_string(n) +
                          " numbers, got shape " + shapeText(array));
  }
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    v(i) = array.at(i);
    if (!std::isfinite(v(i))) {
      std::ostringstream text;
      text << name << "[" << i << "] must be finite, got " << v(i);
      throw py::value_error(text.str());
    }
  }
  return v;
}

const PythonShape& superellipsoidOfPair(const fcl::CollisionGeometry<double>& a,
                                        const fcl::CollisionGeometry<double>& b, bool& shape_first,
                                        const char* call) {
  if (const auto* s = dynamic_cast<const PythonShape*>(&a)) {
    shape_first = true;
    return *s;
  }
  if (const auto* s = dynamic_cast<const PythonShape*>(&b)) {
    shape_first = false;
    return *s;
  }
  throw py::type_error(std::string(call) + ": one of the two shapes must be a Superellipsoid");
}

py::handle resultType(py::module_& m, const char* name, std::initializer_list<const char*> fields,
                      const char* doc) {
  py::tuple names(fields.size());
  std::size_t i = 0;
  for (const char* field : fields) names[i++] = py::str(field);
  py::object type = py::module_::import("collections").attr("namedtuple")(name, names);
  type.attr("__doc__") = doc;
  type.attr("__module__") = "fcl_superellipsoid";
  m.attr(name) = type;
  return type;  // the module's attribute keeps it
}

template <typename S>
py::array_t<S> arrayOver(const S* data, Eigen::Index rows, bool vector3, py::object owner) {
  const auto item = static_cast<py::ssize_t>(sizeof(S));
  if (vector3) {
    return py::array_t<S>({static_cast<py::ssize_t>(rows), py::ssize_t{3}}, {3 * item, item}, data,
                          owner);
  }
  return py::array_t<S>({static_cast<py::ssize_t>(rows)}, {item}, data, owner);
}

template class PointColumns<float>;
template class PointColumns<double>;
template py::array_t<float> arrayOver(const float*, Eigen::Index, bool, py::object);
template py::array_t<double> arrayOver(const double*, Eigen::Index, bool, py::object);

}  // namespace python
}  // namespace fcl_superellipsoid
