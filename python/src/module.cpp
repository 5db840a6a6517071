// The module fcl_superellipsoid._core; the package's __init__.py re-exports it (docs/python.md).
#include <fcl_superellipsoid/batch_distance.h>

#include "bindings.h"

PYBIND11_MODULE(_core, m) {
  namespace python = fcl_superellipsoid::python;
  m.doc() = "The superellipsoid collision geometry for FCL, on numpy arrays.";
  m.attr("simd_instruction_set") = fcl_superellipsoid::simdInstructionSet();
  python::ShapeClass shape = python::bindShape(m);
  python::bindPointQueries(m, shape);
  python::bindPairQueries(m);
  python::bindDerivativeQueries(m, shape);
  python::bindManifoldQueries(m);
}
