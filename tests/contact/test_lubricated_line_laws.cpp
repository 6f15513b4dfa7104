// The lubricated line-contact laws (contact/laws/lubricated_line_contact.hpp, seed 003 section 2.2)
// against closed forms and the conformance checks of a contact law: Martin's rigid-isoviscous load
// recomputed from the Reynolds equation, the elastic-piezoviscous limit of Moes, the inverse film
// thickness, continuity at the film's onset and the dry limit, derivatives against finite
// differences, Poiseuille and Couette traction, and the hydrodynamic roller/cage film against the
// closed-form squeeze force with its passage to the dry contact.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/laws/line_contact.hpp"
#include "contact/laws/lubricated_line_contact.hpp"

namespace raceway::contact {
namespace {

constexpr double pi = std::numbers::pi;

/// A roller on an inner race of a planet bearing: steel, R = 1/(1/r_roller + 1/r_race), a mineral oil.
LineFilm ehd_film(double cutoff = 0) {
  LineFilm f;
  f.viscosity = 0.01;
  f.pressure_viscosity = 2e-8;
  f.reduced_modulus = reduced_modulus(208e9, 0.3, 208e9, 0.3);
  f.reduced_radius = 1.0 / (1.0 / 7e-3 + 1.0 / 30e-3);
  f.length = 20e-3;
  f.cutoff = cutoff;
  return f;
}

EhdLineLaw ehd_law(double cutoff) {
  EhdLineLaw law;
  law.film = ehd_film(cutoff);
  law.stiffness = palmgren_stiffness(law.film.reduced_modulus, law.film.length);
  law.max_approach = 1e-4;
  return law;
}

/// Simpson's rule over [a, b] with n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
  return s * h / 3;
}

// Martin: the Reynolds equation of a rigid cylinder on a plane, h = h0 (1 + X^2), x = sqrt(2 R h0) X,
// dP/dX = (X^2 - Xc^2) / (1 + X^2)^3 with Reynolds' condition P = dP/dX = 0 at the outlet Xc. With
// X = tan(g), dP = (sin^2 g - Xc^2 cos^2 g) cos^2 g dg. The load w = 24 eta u_m R / h0 * int P dX,
// so M_1 H_m = 12 int P dX. Solved here by bisection on Xc and quadrature, independently of the law.
TEST(LubricatedLineLaws, MartinConstantFromTheReynoldsEquation) {
  const auto pressure = [](double g, double gc) {  // P at X = tan(g), from the inlet g = -pi/2
    const double c2 = std::tan(gc) * std::tan(gc);
    return simpson([&](double s) { return (std::sin(s) * std::sin(s) - c2 * std::cos(s) * std::cos(s)) *
                                          std::cos(s) * std::cos(s); },
                   -pi / 2, g, 2000);
  };
  double lo = 0.1, hi = 1.0;  // P(Xc) = 0 at the outlet
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (pressure(mid, mid) > 0 ? lo : hi) = mid;  // P(Xc) > 0: the outlet is further on
  }
  const double gc = 0.5 * (lo + hi);
  // int P dX = int P(g) / cos^2(g) dg.
  const double integral =
      simpson([&](double g) { return g <= -pi / 2 + 1e-9 ? 0.0 : pressure(g, gc) / (std::cos(g) * std::cos(g)); },
              -pi / 2, gc, 400);
  const double constant = 12.0 * integral;
  std::printf("[ martin ] outlet X_c = %.6f, M_1 H_m = %.6f; seed 003 eq. 9's 3 is %.5f times it\n", std::tan(gc),
              constant, 3.0 / constant);
  EXPECT_NEAR(std::tan(gc), 0.47513, 1e-4);
  EXPECT_NEAR(constant, martin_load_constant, 2e-4);
  EXPECT_NEAR(3.0 / martin_load_constant, 1.2257, 1e-3);
}

// Isoviscous (alpha = 0): the law is Martin's w_1 = 2 C_M eta u_m R / h at every thickness; the inverse
// gives the thickness back.
TEST(LubricatedLineLaws, RigidIsoviscousLimit) {
  LineFilm f = ehd_film();
  f.pressure_viscosity = 0;
  for (const double u : {0.1, 3.0, 20.0})
    for (const double h : {1e-8, 1e-6, 1e-4}) {
      const double martin = 2 * martin_load_constant * f.viscosity * u * f.reduced_radius / h;
      EXPECT_NEAR(film_load_per_length(f, h, u), martin, 1e-12 * martin);
      EXPECT_NEAR(film_thickness(f, martin, u), h, 1e-9 * h);
    }
}

// Heavy load, piezoviscous steel contact: the film is Moes' PVE one, H_m = 1.31 L^(3/4) M_1^(-1/8), in
// dimensional form h = 1.31 R sqrt(U) L^(3/4) M_1^(-1/8) (the IVR film is 70 times thinner here),
// with Moes' reduced modulus 2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2 written out here (E' = 2 E*; with
// E' = E* the film would be 2^(-1/8), 8 %, thinner).
TEST(LubricatedLineLaws, ElasticPiezoviscousLimit) {
  const LineFilm f = ehd_film();
  const double e_prime = 2.0 / (2 * (1 - 0.3 * 0.3) / 208e9);
  EXPECT_NEAR(moes_modulus(f), e_prime, 1e-12 * e_prime);
  for (const double u : {5.0, 20.0})
    for (const double w : {2e5, 1e6, 4e6}) {  // N/m
      const double U = 2 * f.viscosity * u / (e_prime * f.reduced_radius);
      const double L = f.pressure_viscosity * e_prime * std::pow(U, 0.25);
      const double M = w / (e_prime * f.reduced_radius * std::sqrt(U));
      const double pve = 1.31 * f.reduced_radius * std::sqrt(U) * std::pow(L, 0.75) * std::pow(M, -0.125);
      const double ivr = martin_load_constant * f.reduced_radius * std::sqrt(U) / M;
      ASSERT_GT(pve, 20 * ivr);
      EXPECT_NEAR(film_thickness(f, w, u), pve, 1e-4 * pve) << "u " << u << " w " << w;
    }
}

// Derivatives of the film's load against central differences, in the IVR, transition, PVE and
// cutoff-window ranges.
TEST(LubricatedLineLaws, FilmLoadDerivatives) {
  const LineFilm f = ehd_film(20e-6);
  for (const double u : {0.5, 5.0, 30.0})
    for (const double h : {5e-8, 2e-7, 1e-6, 5e-6, 12e-6, 18e-6}) {
      double dh = 0, du = 0;
      film_load_per_length(f, h, u, &dh, &du);
      const double eh = 1e-6 * h, eu = 1e-6 * u;
      const double fd_h = (film_load_per_length(f, h + eh, u) - film_load_per_length(f, h - eh, u)) / (2 * eh);
      const double fd_u = (film_load_per_length(f, h, u + eu) - film_load_per_length(f, h, u - eu)) / (2 * eu);
      EXPECT_NEAR(dh, fd_h, 1e-6 * std::abs(fd_h) + 1e-9) << "h " << h << " u " << u;
      EXPECT_NEAR(du, fd_u, 1e-6 * std::abs(fd_u) + 1e-9) << "h " << h << " u " << u;
    }
}

// The EHD contact: the film's load at the film thickness found equals Palmgren's force of the
// deflection (the balance seed 003 2.2.2 asks for); without entrainment it is the dry Palmgren
// contact; the force rises as the gap closes.
TEST(LubricatedLineLaws, EhdBalanceAndDryLimit) {
  const EhdLineLaw law = ehd_law(20e-6);
  double previous = 0;
  for (const double gap : {19e-6, 5e-6, 1e-6, 1e-7, 0.0, -1e-6, -5e-6, -2e-5}) {
    const EhdState s = evaluate_ehd(law, gap, 10.0);
    ASSERT_TRUE(s.valid);
    EXPECT_NEAR(s.film_thickness, gap + s.deflection, 1e-12 * std::abs(gap) + 1e-20);
    const double elastic = law.stiffness * std::pow(s.deflection, palmgren_exponent);
    EXPECT_NEAR(s.force, elastic, 1e-9 * elastic + 1e-12);
    EXPECT_NEAR(s.force, law.film.length * film_load_per_length(law.film, s.film_thickness, 10.0), 1e-9 * s.force);
    EXPECT_GT(s.force, previous) << "gap " << gap;
    previous = s.force;
    const EhdState dry = evaluate_ehd(law, gap, 0.0);
    const double palmgren = gap < 0 ? law.stiffness * std::pow(-gap, palmgren_exponent) : 0.0;
    EXPECT_DOUBLE_EQ(dry.force, palmgren);
    // A film is thicker under a lighter contact: a slower entrainment brings it towards the dry one.
    const EhdState slow = evaluate_ehd(law, gap, 1e-3);
    EXPECT_LE(slow.film_thickness, s.film_thickness);
  }
  // A heavily loaded contact: the film is a fraction of a micrometre and the force Palmgren's to 1 %.
  const EhdState heavy = evaluate_ehd(law, -2e-5, 10.0);
  const double palmgren = law.stiffness * std::pow(2e-5, palmgren_exponent);
  EXPECT_GT(heavy.film_thickness, 1e-8);
  EXPECT_LT(heavy.film_thickness, 1e-6);
  EXPECT_NEAR(heavy.force / palmgren, 1.0, 0.1);
}

// Continuity at onset: the film starts at the cutoff; force and its slope vanish there (C1 window),
// and the force is zero beyond.
TEST(LubricatedLineLaws, EhdContinuousAtOnset) {
  const double cutoff = 20e-6;
  const EhdLineLaw law = ehd_law(cutoff);
  EXPECT_EQ(evaluate_ehd(law, cutoff, 10.0).force, 0.0);
  EXPECT_EQ(evaluate_ehd(law, 2 * cutoff, 10.0).force, 0.0);
  const double inside = evaluate_ehd(law, 0.5 * cutoff, 10.0).force;
  for (const double below : {1e-8, 1e-9}) {
    const EhdState s = evaluate_ehd(law, cutoff - below, 10.0);
    EXPECT_LT(s.force, inside * 30 * (below / cutoff) * (below / cutoff)) << below;  // quadratic onset
    EXPECT_LT(std::abs(s.d_force_d_gap), inside * 30 * below / (cutoff * cutoff)) << below;
  }
}

// Derivatives of the EHD force in gap and entrainment speed (implicit in the balance) against
// central differences of the solved force.
TEST(LubricatedLineLaws, EhdJacobianAgainstFiniteDifferences) {
  const EhdLineLaw law = ehd_law(20e-6);
  for (const double u : {0.3, 3.0, 15.0})
    for (const double gap : {15e-6, 2e-6, 1e-7, -1e-6, -1e-5}) {
      const EhdState s = evaluate_ehd(law, gap, u);
      const double eg = 1e-10, eu = 1e-6 * u;
      const double fd_g = (evaluate_ehd(law, gap + eg, u).force - evaluate_ehd(law, gap - eg, u).force) / (2 * eg);
      const double fd_u = (evaluate_ehd(law, gap, u + eu).force - evaluate_ehd(law, gap, u - eu).force) / (2 * eu);
      EXPECT_NEAR(s.d_force_d_gap, fd_g, 1e-5 * std::abs(fd_g) + 1e-3) << "gap " << gap << " u " << u;
      EXPECT_NEAR(s.d_force_d_speed, fd_u, 1e-5 * std::abs(fd_u) + 1e-6) << "gap " << gap << " u " << u;
      EXPECT_LT(s.d_force_d_gap, 0.0);
    }
}

// Seed 003 eq. 10: the two branches of the Poiseuille force meet at M_1 = (1.47/1.42)^2; the IVR
// branch grows like sqrt(M_1), the PVE one does not depend on the load; the scale E' R U^0.75 with
// E' = 2 E* (E* would make the saturated force 2^(-1/4), 16 %, smaller).
TEST(LubricatedLineLaws, PoiseuilleForce) {
  const LineFilm f = ehd_film();
  const double e_prime = 2.0 / (2 * (1 - 0.3 * 0.3) / 208e9);  // Moes' E' = 2 E*
  const double U = 1e-10, scale = e_prime * f.reduced_radius * std::pow(U, 0.75);
  const double meet = std::pow(1.47 / 1.42, 2);
  EXPECT_NEAR(meet, 1.0717, 1e-4);
  EXPECT_NEAR(poiseuille_force_per_length(f, U, meet * (1 - 1e-12)), 1.47 * scale, 1e-9 * scale);
  EXPECT_DOUBLE_EQ(poiseuille_force_per_length(f, U, 5.0), 1.47 * scale);
  EXPECT_DOUBLE_EQ(poiseuille_force_per_length(f, U, 50.0), 1.47 * scale);
  EXPECT_NEAR(poiseuille_force_per_length(f, U, 0.25), 1.42 * 0.5 * scale, 1e-12 * scale);
  EXPECT_NEAR(poiseuille_force_per_length(f, 16 * U, 0.25) / poiseuille_force_per_length(f, U, 0.25), 8.0, 1e-12);
}

// Couette: nothing in pure rolling, linear in the slide-to-roll ratio with slope mu_max / S_0, odd,
// saturating at mu_max.
TEST(LubricatedLineLaws, CouetteTraction) {
  const CouetteTraction c{0.06, 0.05, 0.01};
  EXPECT_EQ(c.coefficient(0.0, 10.0), 0.0);
  const double slope = c.coefficient(1e-4, 10.0) / (1e-4 / std::hypot(10.0, 0.01));
  EXPECT_NEAR(slope, 0.06 / 0.05, 1e-6);
  EXPECT_DOUBLE_EQ(c.coefficient(-0.3, 10.0), -c.coefficient(0.3, 10.0));
  EXPECT_NEAR(c.coefficient(5.0, 10.0), 0.06, 1e-6);
  EXPECT_EQ((CouetteTraction{0.0, 0.05, 0.01}.coefficient(1.0, 1.0)), 0.0);
}

HydrodynamicLineLaw cage_film(double floor) {
  HydrodynamicLineLaw law;
  law.film.viscosity = 0.01;
  law.film.reduced_radius = 7e-3;  // roller on a flat bar
  law.film.length = 20e-3;
  law.film.cutoff = 200e-6;
  law.film_floor = floor;
  law.dry = make_line_contact_law(reduced_modulus(208e9, 0.3, 100e9, 0.34), 20e-3, 1, 0, 0.5, 1e-4);
  return law;
}

// The squeeze film against its closed form: the pressure of a cylinder approaching a plane at
// dh/dt, p(x) = 6 eta R (-dh/dt) / h(x)^2 with h = h0 + x^2 / 2R (full film), integrated here by
// quadrature, against the law's 3 sqrt(2) pi eta R^1.5 (-dh/dt) / h0^1.5 per unit length.
TEST(LubricatedLineLaws, SqueezeForceClosedForm) {
  const HydrodynamicLineLaw law = cage_film(1e-9);
  const double eta = law.film.viscosity, R = law.film.reduced_radius;
  for (const double h0 : {2e-6, 10e-6, 40e-6})
    for (const double rate : {-0.01, -0.5}) {
      const double width = 200 * std::sqrt(2 * R * h0);  // +-200 contact widths: the tail is 1e-8
      const double per_length = simpson([&](double x) {
        const double h = h0 + x * x / (2 * R);
        return 6 * eta * R * (-rate) / (h * h);
      }, -width, width, 400000);
      const HydrodynamicForce f = evaluate_hydrodynamic(law, h0, rate, 0.0);
      EXPECT_NEAR(f.film_force, law.film.length * per_length, 2e-4 * f.film_force) << "h0 " << h0;
      EXPECT_EQ(f.dry.force, 0.0);
      // A separating film cavitates: nothing.
      EXPECT_EQ(evaluate_hydrodynamic(law, h0, -rate, 0.0).film_force, 0.0);
      // Rolling alone carries Martin's load.
      const double rolling = evaluate_hydrodynamic(law, h0, 0.0, 4.0).film_force;
      EXPECT_NEAR(rolling, law.film.length * 2 * martin_load_constant * eta * 4.0 * R / h0, 1e-3 * rolling);
    }
}

// When the film collapses the dry contact takes over smoothly: the force is continuous through
// touch (gap 0), the film part stays bounded by its value at the floor, and deep in the overlap the
// dry Palmgren force dominates.
TEST(LubricatedLineLaws, HydrodynamicToDryTransition) {
  const HydrodynamicLineLaw law = cage_film(0.5e-6);
  const double rate = -0.2, u = 2.0;
  double previous = 0;
  for (double gap = 5e-6; gap > -5e-6; gap -= 1e-8) {
    const HydrodynamicForce f = evaluate_hydrodynamic(law, gap, rate, u);
    ASSERT_TRUE(f.valid);
    EXPECT_GT(f.force, previous - 1e-9) << "gap " << gap;  // rises as the gap closes
    if (previous > 0) {
      EXPECT_LT(f.force - previous, 0.05 * previous + 1.0) << "gap " << gap;  // no jump
    }
    previous = f.force;
    EXPECT_GE(f.film_thickness, law.film_floor);
  }
  // The film part is bounded by its value at the floor: h = floor at most (1 + sqrt 2) / 2 times
  // thinner than at touch, so at most 1.207^1.5 = 1.33 times the squeeze force at touch.
  const HydrodynamicForce deep = evaluate_hydrodynamic(law, -5e-6, rate, u);
  EXPECT_LT(deep.film_force, 1.33 * evaluate_hydrodynamic(law, 0.0, rate, u).film_force);
  // A slow approach: the dry contact carries nearly everything.
  const HydrodynamicForce slow = evaluate_hydrodynamic(law, -5e-6, -1e-3, 0.0);
  EXPECT_GT(slow.dry.force, 10 * slow.film_force);
  // Without motion there is no film: exactly the dry contact.
  const HydrodynamicForce still = evaluate_hydrodynamic(law, -1e-6, 0.0, 0.0);
  EXPECT_EQ(still.film_force, 0.0);
  EXPECT_DOUBLE_EQ(still.force, evaluate_normal(law.dry, 1e-6, 0.0).force);
}

}  // namespace
}  // namespace raceway::contact
