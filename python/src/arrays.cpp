// Lists of vectors and index tuples as NumPy arrays, and collision bit sets, checked on the way in.
#include "bindings.h"

namespace tandem::python {
namespace {

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

template <class Scalar>
py::array_t<Scalar, py::array::c_style | py::array::forcecast> matrixOf(const py::handle& source, py::ssize_t columns,
                                                                       const char* what) {
  auto array = py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(source);
  if (!array) throw py::value_error(std::string(what) + ": expected an array of numbers");
  // An empty list is an empty (0, K) array.
  if (array.size() == 0)
    return py::array_t<Scalar, py::array::c_style | py::array::forcecast>(std::vector<py::ssize_t>{0, columns});
  if (array.ndim() != 2 || array.shape(1) != columns)
    throw py::value_error(std::string(what) + ": expected an (N, " + std::to_string(columns) + ") array, got shape " +
                          shapeText(array));
  return array;
}

}  // namespace

py::array_t<double> toArray(const std::vector<Vec3>& vectors) {
  py::array_t<double> array({static_cast<py::ssize_t>(vectors.size()), py::ssize_t{3}});
  auto out = array.mutable_unchecked<2>();
  for (size_t i = 0; i < vectors.size(); ++i)
    for (int k = 0; k < 3; ++k) out(static_cast<py::ssize_t>(i), k) = vectors[i][k];
  return array;
}

std::vector<Vec3> toVec3s(const py::handle& source, const char* what) {
  auto array = matrixOf<double>(source, 3, what);
  auto in = array.unchecked<2>();
  std::vector<Vec3> vectors(static_cast<size_t>(array.shape(0)));
  for (py::ssize_t i = 0; i < array.shape(0); ++i) vectors[static_cast<size_t>(i)] = Vec3(in(i, 0), in(i, 1), in(i, 2));
  return vectors;
}

py::array_t<double> toArray(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

std::vector<double> toDoubles(const py::handle& source, const char* what) {
  auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(source);
  if (!array || array.ndim() > 1)
    throw py::value_error(std::string(what) + ": expected a 1-D array of numbers" +
                          (array ? ", got shape " + shapeText(array) : std::string()));
  return std::vector<double>(array.data(), array.data() + array.size());
}

uint32_t toCollisionBits(int64_t value, const char* what) {
  if (value < 0 || value > static_cast<int64_t>(UINT32_MAX))
    throw py::value_error(std::string(what) + " must be in [0, 2**32) (a set of 32 bits; tandem.ALL_COLLISION_GROUPS "
                          "is every group), got " + std::to_string(value));
  return static_cast<uint32_t>(value);
}

template <size_t K>
py::array_t<int32_t> toArray(const std::vector<std::array<int32_t, K>>& tuples) {
  py::array_t<int32_t> array({static_cast<py::ssize_t>(tuples.size()), static_cast<py::ssize_t>(K)});
  auto out = array.mutable_unchecked<2>();
  for (size_t i = 0; i < tuples.size(); ++i)
    for (size_t k = 0; k < K; ++k) out(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = tuples[i][k];
  return array;
}

template <size_t K>
std::vector<std::array<int32_t, K>> toIndexTuples(const py::handle& source, const char* what) {
  // Through int64 so that an index beyond int32 is refused, not wrapped round.
  auto array = matrixOf<int64_t>(source, static_cast<py::ssize_t>(K), what);
  auto in = array.unchecked<2>();
  std::vector<std::array<int32_t, K>> tuples(static_cast<size_t>(array.shape(0)));
  for (py::ssize_t i = 0; i < array.shape(0); ++i)
    for (size_t k = 0; k < K; ++k) {
      const int64_t index = in(i, static_cast<py::ssize_t>(k));
      if (index < INT32_MIN || index > INT32_MAX)
        throw py::value_error(std::string(what) + ": index " + std::to_string(index) + " is out of range");
      tuples[static_cast<size_t>(i)][k] = static_cast<int32_t>(index);
    }
  return tuples;
}

template py::array_t<int32_t> toArray<2>(const std::vector<std::array<int32_t, 2>>&);
template py::array_t<int32_t> toArray<3>(const std::vector<std::array<int32_t, 3>>&);
template py::array_t<int32_t> toArray<4>(const std::vector<std::array<int32_t, 4>>&);
template std::vector<std::array<int32_t, 2>> toIndexTuples<2>(const py::handle&, const char*);
template std::vector<std::array<int32_t, 3>> toIndexTuples<3>(const py::handle&, const char*);
template std::vector<std::array<int32_t, 4>> toIndexTuples<4>(const py::handle&, const char*);

}  // namespace tandem::python
