#pragma once
// Second-order spherical-harmonics shading basis, as written in the paper
// (§4.3, eq. 4.7): SH(n) = (1, nx, ny, nz, nx ny, nx nz, ny nz, nx^2 - ny^2, 3 nz^2 - 1).
// The irradiance of a Lambertian point with albedo rho and unit normal n is
// rho * l^T SH(n), with one 9-vector l of lighting coefficients shared by the
// three colour channels.
#include <Eigen/Core>

namespace facecap {

using ShCoeffs = Eigen::Matrix<double, 9, 1>;

template <typename T>
inline Eigen::Matrix<T, 9, 1> sh_basis(T nx, T ny, T nz) {
  Eigen::Matrix<T, 9, 1> b;
  b << T(1), nx, ny, nz, nx * ny, nx * nz, ny * nz, nx * nx - ny * ny, T(3) * nz * nz - T(1);
  return b;
}

template <typename T>
inline T sh_shade(const ShCoeffs& l, T nx, T ny, T nz) {
  return T(l[0]) + T(l[1]) * nx + T(l[2]) * ny + T(l[3]) * nz + T(l[4]) * nx * ny + T(l[5]) * nx * nz +
         T(l[6]) * ny * nz + T(l[7]) * (nx * nx - ny * ny) + T(l[8]) * (T(3) * nz * nz - T(1));
}

}  // namespace facecap
