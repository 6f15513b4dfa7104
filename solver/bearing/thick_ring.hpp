// The in-plane harmonics of a thick circular ring (a curved Timoshenko beam): bending, extension
// of the centre line and transverse shear, for the flexible outer ring's modes (ring_modes.hpp).
//
// Displacements of harmonic n (the cos family; the sin family is the same turned by pi / 2n):
// radial w = W cos(n theta) (outward), tangential v = V sin(n theta), the sections' rotation
// psi = Psi sin(n theta). Strains of the centre line (radius R, s = R theta):
//
//   extension  eps   = (v' + w) / R                    (' = d/dtheta)
//   bending    kappa = psi' / R - eps / R              (the change of the centre line's curvature)
//   shear      gamma = psi - (v - w') / R
//
// and the strain energy per length (E A eps^2 + E I / (1 - alpha) kappa^2 + k_s G A gamma^2) / 2,
// alpha = I / (A R^2). That is the curved beam's energy as Roark's thick-ring formulas use it
// (docs/references.md): in stress resultants M^2 / (2 E I) + N^2 / (2 E A) - M N / (E A R) +
// V^2 / (2 k_s G A), whose M N term is the curved beam's (its neutral axis lies inside the
// centroid) and gives the bending stiffness its 1 / (1 - alpha); k_s is Cowper's shear
// coefficient of the rectangle, 10 (1 + nu) / (12 + 11 nu). Thin and inextensional (A, G A -> oo)
// it is Love's ring, whose harmonic n >= 2 has W = 1, V = -1/n.
//
// One coordinate per harmonic and family, the amplitude W of the radial displacement, with V and
// Psi those of the static response to a radial load cos(n theta) (V, Psi condensed): a radial
// load's static deflection is then exact for every harmonic, a tangential load's (friction) is
// Rayleigh-Ritz. n = 0 is the breathing of the rim (w uniform, its stretch), n = 1 the shape
// (W, V) = (1, 1) with Psi condensed: it stretches and shears the rim and is orthogonal (in mass)
// to the ring's translation (1, -1), which is the ring body's. The mass for W is Rayleigh's, with
// the sections' rotary inertia.
#pragma once

namespace raceway::bearing {

/// A thick ring's section and mass.
struct ThickRingSection {
  double radius = 0;              ///< m, of the centre line
  double youngs_modulus = 0;      ///< Pa
  double shear_modulus = 0;       ///< Pa
  double shear_coefficient = 0;   ///< k_s
  double area = 0, area_moment = 0;  ///< m^2, m^4 (in-plane bending)
  double mass_per_length = 0;     ///< kg/m, translation
  double rotary_per_length = 0;   ///< kg m, the sections' rotary inertia per length
};

/// A rectangular section thickness x width (radial x axial) of a material (E, nu) at the centre
/// radius `radius`, the ring's mass `mass_per_length` spread round it (the rotary inertia in
/// proportion: mass_per_length thickness^2 / 12).
ThickRingSection rectangular_ring(double radius, double thickness, double width, double youngs_modulus,
                                  double poisson_ratio, double mass_per_length);

/// Harmonic n's coordinate: stiffness and mass for W, and the shape's V / W, Psi / W.
struct RingHarmonic {
  double stiffness = 0;  ///< N/m: the generalized force integral p_r cos(n theta) R dtheta per W
  double mass = 0;       ///< kg
  double tangential = 0;  ///< V / W
  double rotation = 0;    ///< Psi / W, 1/m
};
RingHarmonic thick_ring_harmonic(const ThickRingSection& ring, int n);

}  // namespace raceway::bearing
