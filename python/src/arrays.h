#pragma once
// Arrays in and out of the module: configuration rows from numpy, verdicts back.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <cstdint>

namespace gplanner::python {

// Configuration rows as the checker reads them: shape [n, width] row-major float32.
// `data` points into the caller's array where it is already C-contiguous float32 (no
// copy), else into `owned`, a float32 copy.
struct Rows {
  pybind11::array_t<float> owned;
  pybind11::object keep;  // the array `data` points into
  const float* data = nullptr;
  std::size_t n = 0;
};

// `value` as rows of `width` floats: a numpy array (or anything numpy.asarray takes) of
// float32 or float64, shape [n, width] or [width] (one row). Throws TypeError naming
// `name` and the dtype for any other dtype, ValueError naming the shape expected and
// given. NaN or infinite entries are kept: the checker reports such rows colliding, as
// gplan does.
Rows rows_of(pybind11::handle value, int width, const char* name);

// A new numpy bool array of n, and a pointer to its bytes (0 or 1) for a checker.
pybind11::array_t<bool> new_verdicts(std::size_t n, std::uint8_t** bytes);

}  // namespace gplanner::python
