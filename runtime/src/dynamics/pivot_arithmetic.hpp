// The complex arithmetic of the LU factorisations' pivots (small_lu.cpp, band_lu.cpp). Internal header.
#pragma once

#include <complex>

namespace mbgen::detail {

// |z|^2: pivots are compared by it (no hypot).
inline double norm2(std::complex<double> z) { return z.real() * z.real() + z.imag() * z.imag(); }

// 1 / z without the library's overflow-guarded complex division (z is a pivot: non-zero, finite, of moderate size).
inline std::complex<double> reciprocal(std::complex<double> z) {
  const double d = norm2(z);
  return {z.real() / d, -z.imag() / d};
}

}  // namespace mbgen::detail
