#include "arrays.h"

#include <string>

namespace py = pybind11;

namespace gplanner::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

Rows rows_of(py::handle value, int width, const char* name) {
  py::array a = py::module_::import("numpy").attr("asarray")(value);
  const py::dtype dtype = a.dtype();
  if (dtype.kind() != 'f' || (dtype.itemsize() != 4 && dtype.itemsize() != 8)) {
    throw py::type_error(std::string(name) + ": float32 or float64 rows expected, got dtype " +
                         py::str(py::object(dtype)).cast<std::string>());
  }
  const bool one_row = a.ndim() == 1 && a.shape(0) == width;
  if (!one_row && !(a.ndim() == 2 && a.shape(1) == width)) {
    throw py::value_error(std::string(name) + ": shape (N, " + std::to_string(width) +
                          ") expected (this scene's configurations have " + std::to_string(width) +
                          " values), got " + shape_text(a));
  }
  Rows rows;
  rows.n = one_row ? 1 : static_cast<std::size_t>(a.shape(0));
  if (dtype.itemsize() == 4 && (a.flags() & py::array::c_style)) {
    rows.keep = a;
    rows.data = static_cast<const float*>(a.data());
  } else {
    rows.owned = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!rows.owned) throw py::error_already_set();
    rows.data = rows.owned.data();
  }
  return rows;
}

py::array_t<bool> new_verdicts(std::size_t n, std::uint8_t** bytes) {
  py::array_t<bool> verdicts(static_cast<py::ssize_t>(n));
  *bytes = reinterpret_cast<std::uint8_t*>(verdicts.mutable_data());
  return verdicts;
}

}  // namespace gplanner::python
