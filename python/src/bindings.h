// Shared pieces of the `tandem` Python module: the bind functions each file defines, errors,
// keyword construction of plain structs, quaternions and arrays of vectors.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <tandem/types.h>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;

// Quaternions cross into Python as 4 floats (w, x, y, z), the order of the record CSV's columns.
namespace pybind11::detail {
template <>
struct type_caster<Eigen::Quaterniond> {
  PYBIND11_TYPE_CASTER(Eigen::Quaterniond, const_name("numpy.ndarray[numpy.float64[4]]"));

  bool load(handle source, bool convert) {
    if (!convert && !isinstance<array_t<double>>(source)) return false;
    auto values = array_t<double, array::c_style | array::forcecast>::ensure(source);
    if (!values || values.ndim() != 1 || values.shape(0) != 4) return false;
    value = Eigen::Quaterniond(values.at(0), values.at(1), values.at(2), values.at(3));
    return true;
  }
  static handle cast(const Eigen::Quaterniond& quat, return_value_policy, handle) {
    array_t<double> values(4);
    auto out = values.mutable_unchecked<1>();
    out(0) = quat.w();
    out(1) = quat.x();
    out(2) = quat.y();
    out(3) = quat.z();
    return values.release();
  }
};
}  // namespace pybind11::detail

namespace tandem::python {

// A library error (a Status or Result holding an Error) on its way to Python as tandem.Error,
// with the library's message unchanged.
class LibraryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An id the world does not hold (never made, or stale: what it named was removed), on its way to
// Python as tandem.IdError, which is both a tandem.Error and an IndexError.
class IdError : public LibraryError {
 public:
  using LibraryError::LibraryError;
};

inline void check(const Status& status) {
  if (!status) throw LibraryError(status.message());
}
template <class T>
T unwrap(Result<T>&& result) {
  if (!result) throw LibraryError(result.message());
  return std::move(result).value();
}

// Sets the attributes named by `kwargs` on a bound struct: `RigidBodyDesc(name="box", mass=2)`.
// An unknown name is a TypeError naming it and the type.
template <class T>
void setFields(T& target, const py::kwargs& kwargs) {
  py::object self = py::cast(&target, py::return_value_policy::reference);
  for (auto item : kwargs) {
    const std::string name = py::str(item.first);
    if (name.starts_with("_") || !py::hasattr(py::type::of(self), name.c_str()))
      throw py::type_error(std::string(py::str(py::type::of(self).attr("__name__"))) + ": no field named '" + name + "'");
    self.attr(name.c_str()) = item.second;
  }
}

// A keyword constructor for a bound struct with default values.
template <class T, class Class>
void defKeywordInit(Class& cls) {
  cls.def(py::init([](const py::kwargs& kwargs) {
            T value;
            setFields(value, kwargs);
            return value;
          }),
          "Defaults, with any field set by keyword.");
}

// Vectors of 3 and index tuples as (N, 3) / (N, K) NumPy arrays (copies) and back. A wrong
// shape is a ValueError naming `what` and the shape.
py::array_t<double> toArray(const std::vector<Vec3>& vectors);
std::vector<Vec3> toVec3s(const py::handle& array, const char* what);
py::array_t<double> toArray(const std::vector<double>& values);
std::vector<double> toDoubles(const py::handle& array, const char* what);
template <size_t K>
py::array_t<int32_t> toArray(const std::vector<std::array<int32_t, K>>& tuples);
template <size_t K>
std::vector<std::array<int32_t, K>> toIndexTuples(const py::handle& array, const char* what);
// A collision group or mask from Python: an int in [0, 2**32), else a ValueError naming `what`.
uint32_t toCollisionBits(int64_t value, const char* what);

// Each file binds one part of the API.
void bindErrors(py::module_& module);
void bindIds(py::module_& module);
void bindSettings(py::module_& module);
void bindRigid(py::module_& module);
void bindMesh(py::module_& module);
void bindDeformable(py::module_& module);
void bindQueries(py::module_& module);
void bindReport(py::module_& module);
void bindWorld(py::module_& module);
void bindScene(py::module_& module);

}  // namespace tandem::python
