// Point-contact laws for ball bearings: Hertz's elliptical contact with exact
// ellipticity, Hamrock-Dowson EHL film, traction integrated over a grid on the contact ellipse from
// the local sliding velocity (including spin), and EHL rolling resistance.
//
// Pure functions of their arguments, SI units throughout. Derived constants (ellipticity, elliptic
// integrals, the load-deflection constant) are computed once when a segment is built and tabulated
// over the one geometric parameter that changes during a run (the contact angle), never per call.
#pragma once

#include <span>
#include <vector>

namespace raceway::contact {

/// The exact Hertz solution for two bodies with principal relative curvatures kx (in the x plane,
/// the rolling direction) and ky (transverse) [1/m], kx + ky > 0, and reduced modulus E* [Pa]
/// (1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2, as in line_contact.hpp).
///
/// Contact ellipse semi-axes a (along the direction of smaller relative curvature) and b, approach
/// delta and load Q are related by Q = stiffness * delta^(3/2),
///   a = a_coefficient * Q^(1/3), b = b_coefficient * Q^(1/3), p_max = 3 Q / (2 pi a b).
/// `a_along_x` tells along which direction a lies. The ellipticity k = a/b >= 1 solves the exact
/// relation between curvature difference and complete elliptic integrals (std::comp_ellint_1/2).
struct HertzPointContact {
  double stiffness = 0;      ///< K [N/m^1.5]
  double ellipticity = 1;    ///< k = a / b >= 1
  double a_coefficient = 0;  ///< [m / N^(1/3)]
  double b_coefficient = 0;  ///< [m / N^(1/3)]
  bool a_along_x = false;    ///< semi-major axis along the rolling direction x
};
/// Exact solution (safeguarded Newton on e^2 = 1 - 1/k^2, converged to round-off; smooth through
/// the circle kx = ky, where k = 1 and K = (4/3) E* sqrt(1/kx)). Formulas and references in
/// point_contact.cpp (Johnson, Contact Mechanics, sec. 4.2; Harris & Kotzalas ch. 6). Throws
/// std::invalid_argument if kx + ky <= 0, if either curvature is <= 0 (no elliptical contact: a
/// line contact or a conforming one) or if E* is not positive and finite.
HertzPointContact hertz_point_contact(double kx, double ky, double reduced_modulus);

/// The Hertz constants tabulated once over a geometric parameter s in [s_min, s_max] (for a
/// ball-race contact: cos of the contact angle, on which the rolling-direction curvature depends),
/// interpolated by cubic Hermite splines (stiffness, a and b coefficients; node derivatives by
/// fourth-order finite differences of the node values); error in stiffness below 1e-4 of exact over
/// the range (for a ball-race contact over s in [0.5, 1]: 3e-13 with 33 nodes, 2e-9 with 5). k = a/b of the
/// interpolated coefficients; a_along_x from the nearest node.
class HertzTable {
 public:
  HertzTable() = default;
  /// curvatures(s, kx, ky) gives the relative curvatures at s. `points` >= 2 nodes, uniform in s.
  template <class CurvatureFunction>
  HertzTable(CurvatureFunction curvatures, double s_min, double s_max, int points, double reduced_modulus);
  /// Constant (s-independent) contact, e.g. a ball in a spherical pocket.
  explicit HertzTable(const HertzPointContact& constant);
  /// Interpolated constants at s (clamped to the table's range; NaN s gives NaN constants).
  HertzPointContact at(double s) const;
  double s_min() const { return s_min_; }
  double s_max() const { return s_max_; }

 private:
  void build(const std::vector<double>& kx, const std::vector<double>& ky, double reduced_modulus);
  double s_min_ = 0, s_max_ = 0;
  std::vector<HertzPointContact> nodes_;
  std::vector<double> d_stiffness_, d_a_, d_b_;  ///< d/ds at the nodes (Hermite)
};

/// Lubricant properties a point contact needs. viscosity = 0 switches the film and rolling
/// resistance off (dry contact; traction then follows the traction curve alone).
struct PointLubricant {
  double viscosity = 0;            ///< eta0 [Pa s] at the bearing temperature
  double pressure_viscosity = 0;   ///< alpha [1/Pa] (Barus)
  double limiting_shear_coefficient = 0;  ///< Lambda: limiting shear stress tau_L = Lambda p [-]
  /// Largest alpha p in the Barus law of the limiting-shear model: an effective-viscosity limit
  /// (shear thinning and heating in the inlet-to-centre shear) that also bounds the initial slope
  /// of the traction curve, eta(p) s / h. 20 (eta0 e^20) makes the curve a near step in slip
  /// (saturation below 1e-5 m/s), which costs the integrator tiny steps; 10-12 gives saturation
  /// at mm/s, the shape of measured traction curves.
  double viscosity_exponent_cap = 20;
  /// Roelands' pressure-viscosity index Z (viscosity.hpp) for the limiting-shear model's viscosity; 0:
  /// Barus, exp(alpha p). Either way ln(eta / eta0) is capped at viscosity_exponent_cap.
  double roelands_index = 0;
  /// Film thickness [m] at and above which the film carries the whole traction. Below it, as the
  /// film vanishes (the entrainment speed going to zero: standstill, start and stop), the film's
  /// shear hands over to the friction curve by film_weight, so that the traction stays continuous
  /// with a bounded slope: the film's own slope eta / h grows without bound as h -> 0, and it
  /// saturates at Lambda p, not at the curve's mu p. 10 nm is below any running film (tenths of
  /// a micrometre) and below the roughness of ground races, where the film model no longer holds.
  double boundary_film = 1e-8;
  /// Starvation: the inlet meniscus's distance from the contact centre in semi-widths of the contact
  /// along the rolling direction (Hamrock and Dowson's m, starved_film below); 0: fully flooded.
  double inlet_meniscus = 0;
};

/// The share of a point contact's traction carried by the film of central thickness h [m]:
/// 0 at h <= 0, 1 at h >= boundary_film, and x^2 (3 - 2x), x = h / boundary_film, between
/// (C1 at both ends). Its product with the film's shear slope, w eta / h, stays bounded as h -> 0.
double film_weight(double film_thickness, const PointLubricant& lubricant);

/// Hamrock-Dowson EHL film thicknesses for a point contact [m] (fully flooded, isothermal):
///   H_c = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 e^(-0.73 k)),
///   H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - e^(-0.68 k)),
/// with U = eta0 u_e / (E' Rx), G = alpha E', W = Q / (E' Rx^2), E' = 2 E*, Rx the effective
/// radius in the rolling (entrainment) direction, k the ellipticity (Hamrock-Dowson's k = a/b with
/// a transverse to rolling), taken from Hamrock & Brewe's closed form k = 1.0339 (Ry/Rx)^0.636
/// (1.5 % above exact for a 0.52-conformity inner race, 6 % at Ry/Rx = 100; the fit's own k-term
/// 1 - 0.61 e^(-0.73 k) moves by < 0.1 % for that; no iteration per call).
/// h_c = H_c Rx, h_min = H_min Rx. Zero when u_e <= 0, Q <= 0 or viscosity = 0; the fit is for the
/// piezoviscous-elastic regime and gives zero for alpha = 0.
struct FilmThickness {
  double central = 0, minimum = 0;
};
FilmThickness hamrock_dowson_film(double entrainment_speed, double load, double rx, double ry,
                                  double reduced_modulus, const PointLubricant& lubricant);
/// The central film h_c of hamrock_dowson_film alone (the same bits), without the minimum film's work.
double hamrock_dowson_central_film(double entrainment_speed, double load, double rx, double ry,
                                   double reduced_modulus, const PointLubricant& lubricant);

/// Hamrock and Dowson's starved point contact (Hamrock, Fundamentals of Fluid Film Lubrication, the
/// chapter on starvation; docs/lubrication.md says what was checked): the inlet meniscus at m
/// semi-widths b (along the rolling direction) from the contact centre starves the film below the
/// critical m* = 1 + 3.06 ((Rx/b)^2 H_c)^0.58 (central) and 1 + 3.34 ((Rx/b)^2 H_min)^0.56 (minimum),
/// H = h / Rx the fully flooded films; there the films are H ((m - 1)/(m* - 1))^0.29 (central) and
/// ^0.25 (minimum). m <= 0 (flooded), m >= m* or b <= 0: the flooded film unchanged.
FilmThickness starved_film(const FilmThickness& flooded, double rx, double semi_width, double inlet_meniscus);

/// How traction is computed on a point contact.
///  - curve: mu(s) = mu_max tanh(s / s_scale) of the local sliding speed s (regularised Coulomb);
///  - limiting_shear: Newtonian shear limited by tau_L = Lambda p (Eyring-like smooth limit):
///      tau = tau_L tanh(eta(p) s / (h tau_L)),  eta(p) = eta0 exp(min(alpha p, alpha_p_cap)),
///    alpha_p_cap = 20 (eta at most e^20 ~ 5e8 times eta0), with the central film h; falls back to
///    the curve where the film is zero (h <= 0) or the viscosity is 0, and hands over to it
///    continuously below lubricant.boundary_film: w tau_film + (1 - w) tau_curve with
///    w = film_weight(h) (so it works at standstill). Lambda <= 0 gives no shear.
/// Both are smooth at zero slip: the shear is -(tau/s) times the slip vector, tau/s finite at s = 0.
enum class TractionModel { none, curve, limiting_shear };
struct PointTraction {
  TractionModel model = TractionModel::curve;
  double friction_coefficient = 0;  ///< mu_max of the curve [-]
  double slip_velocity_scale = 1;   ///< s_scale of the curve [m/s]
  int grid_x = 5, grid_y = 5;       ///< grid cells over the ellipse (rolling x transverse)
};

/// Sliding at the contact centre and the spin about the common normal, in the contact frame
/// (x rolling direction, y transverse, z = common normal pointing into body 1):
///   sliding velocity of body 2's surface relative to body 1's at a point (x, y) of the contact
///   plane is (slide_x - spin * y, slide_y + spin * x).
struct ContactSliding {
  double slide_x = 0, slide_y = 0;  ///< m/s at the contact centre
  double spin = 0;                  ///< rad/s, relative spin of body 2 on body 1 about z
};

/// Traction integrated over the contact ellipse (semi-axes ax along x, ay along y) with Hertz
/// pressure p(x, y) = p_max sqrt(1 - (x/ax)^2 - (y/ay)^2): force on body 2 in the contact plane
/// (opposing its sliding), moment on body 2 about the normal through the contact centre, and the
/// power dissipated (>= 0). Midpoint rule on grid_x x grid_y cells of the bounding rectangle: each
/// cell weighted by the (exact) area of its overlap with the ellipse, evaluated at the overlap's
/// centroid, and the pressures scaled so that the sum of p times area is exactly Q. The grid is
/// exactly symmetric about both axes (mirrored cells have the same area and pressure bits), so the
/// pressure-dependent viscosity is evaluated once per distinct cell pressure (6 on the 5 x 5 grid),
/// and tanh(x)/x is a rational approximant (|x| <= 1) or one exponential, to about an ulp. The cell
/// tables are built once per (grid_x, grid_y) and thread; a call allocates nothing. The cells are
/// evaluated in a loop the compiler vectorises, each with the bits of the scalar formula, and
/// summed in grid order (contact/laws/point_traction.cpp). Zero for model none,
/// Q <= 0 or a degenerate ellipse; throws std::invalid_argument if grid_x or grid_y < 1.
struct TractionResult {
  double force_x = 0, force_y = 0;  ///< N, on body 2
  double spin_moment = 0;           ///< N m, on body 2 about the normal
  double power_loss = 0;            ///< W
};
TractionResult integrate_traction(const PointTraction& traction, const PointLubricant& lubricant,
                                  double normal_force, double ax, double ay, double film_thickness,
                                  const ContactSliding& sliding);

/// The grid's fixed decomposition into blocks, so that one contact's traction can be computed in
/// parts (by different processes) and still give the same bits. The cells, in grid order (rows
/// along x), are cut into traction_block_count contiguous blocks of about traction_block_cells
/// each (at least 1, at most max_traction_blocks); each block's sums start from zero, and the
/// blocks are added in block order (sum_traction_blocks). integrate_traction is exactly that, so a
/// grid of one block (up to 2 x traction_block_cells - 1 cells, e.g. the default 5 x 5) sums its
/// cells in one pass as before. The block size is a property of the grid alone, never of how many
/// processes share the work: the result is a function of the inputs only.
/// 256 cells: ~5-10 us of work, against ~0.5 us to set up a contact once more per block.
inline constexpr std::size_t traction_block_cells = 256;
inline constexpr int max_traction_blocks = 64;
int traction_block_count(const PointTraction& traction);
/// Block `block` (0 .. traction_block_count - 1) of integrate_traction; the same early returns
/// (all zero) and the same invalid_argument for a grid below 1 x 1, or a block out of range.
TractionResult integrate_traction_block(const PointTraction& traction, const PointLubricant& lubricant,
                                        double normal_force, double ax, double ay, double film_thickness,
                                        const ContactSliding& sliding, int block);
/// The blocks' results added in block order, starting from block 0 (the order every caller uses).
TractionResult sum_traction_blocks(std::span<const TractionResult> blocks);

/// EHL rolling resistance force [N] (hydrodynamic, opposing the rolling direction):
/// F_R = 2.86 E' Rx^2 k^0.348 G^0.022 U^0.66 W^0.47 (Houpert's fit, as quoted by Harris & Kotzalas,
/// Advanced Concepts of Bearing Technology, 2007), E', U, G, W, k as in hamrock_dowson_film. An
/// earlier version of this comment had E' Ry, a force per length; E' Rx^2 is the dimensionally
/// consistent scale (the one of W). Not re-checked against the book (not in the stored literature
/// search corpora). F_R grows as u^0.66, eta0^0.66, Q^0.47, alpha^0.022.
/// Zero where the film is zero (u_e <= 0, Q <= 0, viscosity = 0) and for alpha = 0.
double ehl_rolling_resistance(double entrainment_speed, double load, double rx, double ry,
                              double reduced_modulus, const PointLubricant& lubricant);

// ---- template definition ------------------------------------------------------------------------
template <class CurvatureFunction>
HertzTable::HertzTable(CurvatureFunction curvatures, double s_min, double s_max, int points,
                       double reduced_modulus)
    : s_min_(s_min), s_max_(s_max) {
  std::vector<double> kx(static_cast<std::size_t>(points)), ky(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i) {
    const double s = points > 1 ? s_min + (s_max - s_min) * i / (points - 1) : s_min;
    curvatures(s, kx[static_cast<std::size_t>(i)], ky[static_cast<std::size_t>(i)]);
  }
  build(kx, ky, reduced_modulus);
}

}  // namespace raceway::contact
