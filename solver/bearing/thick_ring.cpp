#include "solver/bearing/thick_ring.hpp"

#include <array>
#include <numbers>

namespace raceway::bearing {

ThickRingSection rectangular_ring(double radius, double thickness, double width, double youngs_modulus,
                                  double poisson_ratio, double mass_per_length) {
  ThickRingSection s;
  s.radius = radius;
  s.youngs_modulus = youngs_modulus;
  s.shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  s.shear_coefficient = 10.0 * (1.0 + poisson_ratio) / (12.0 + 11.0 * poisson_ratio);
  s.area = thickness * width;
  s.area_moment = width * thickness * thickness * thickness / 12.0;
  s.mass_per_length = mass_per_length;
  s.rotary_per_length = mass_per_length * thickness * thickness / 12.0;
  return s;
}

namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

/// The strain energy of harmonic n as (1/2) x^T H x, x = (W, V, Psi).
Matrix3 harmonic_stiffness(const ThickRingSection& r, int n) {
  const double R = r.radius, nn = n;
  const double alpha = r.area_moment / (r.area * R * R);
  struct Strain {
    double weight;
    std::array<double, 3> row;  ///< the strain's amplitude per W, V, Psi
  };
  const Strain strains[3] = {
      {r.youngs_modulus * r.area, {1.0 / R, nn / R, 0.0}},                                   // eps
      {r.youngs_modulus * r.area_moment / (1.0 - alpha), {-1.0 / (R * R), -nn / (R * R), nn / R}},  // kappa
      {r.shear_coefficient * r.shear_modulus * r.area, {-nn / R, -1.0 / R, 1.0}},            // gamma
  };
  const double arc = (n == 0 ? 2.0 : 1.0) * std::numbers::pi * R;  // integral of cos^2 (sin^2) R dtheta
  Matrix3 h{};
  for (const Strain& s : strains)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) h[i][j] += arc * s.weight * s.row[i] * s.row[j];
  return h;
}

}  // namespace

RingHarmonic thick_ring_harmonic(const ThickRingSection& r, int n) {
  const Matrix3 h = harmonic_stiffness(r, n);
  RingHarmonic out;
  if (n == 0) {  // v and psi (sin 0) vanish: w uniform
    out.stiffness = h[0][0];
  } else if (n == 1) {  // V = W fixed (orthogonal to the translation V = -W), Psi condensed
    const double coupling = h[0][2] + h[1][2];
    out.tangential = 1.0;
    out.rotation = -coupling / h[2][2];
    out.stiffness = h[0][0] + 2.0 * h[0][1] + h[1][1] + coupling * out.rotation;
  } else {  // V and Psi condensed: [h11 h12; h12 h22] (V, Psi) = -(h01, h02)
    const double det = h[1][1] * h[2][2] - h[1][2] * h[1][2];
    out.tangential = (-h[0][1] * h[2][2] + h[0][2] * h[1][2]) / det;
    out.rotation = (-h[0][2] * h[1][1] + h[0][1] * h[1][2]) / det;
    out.stiffness = h[0][0] + h[0][1] * out.tangential + h[0][2] * out.rotation;
  }
  const double arc = (n == 0 ? 2.0 : 1.0) * std::numbers::pi * r.radius;
  out.mass = arc * (r.mass_per_length * (1.0 + out.tangential * out.tangential) +
                    r.rotary_per_length * out.rotation * out.rotation);
  return out;
}

}  // namespace raceway::bearing
