#include "contact/laws/lubricated_line_contact.hpp"

#include "contact/laws/reynolds_line_film.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace raceway::contact {

namespace {

/// The cutoff window: 1 up to cutoff/2, a C1 smoothstep down to 0 at the cutoff; its slope.
double film_window(double h, double cutoff, double* slope) {
  if (slope) *slope = 0;
  if (cutoff <= 0 || h <= 0.5 * cutoff) return 1.0;
  if (h >= cutoff) return 0.0;
  const double half = 0.5 * cutoff, t = (h - half) / half;
  if (slope) *slope = -6.0 * t * (1.0 - t) / half;
  return 1.0 - t * t * (3.0 - 2.0 * t);
}

}  // namespace

double moes_modulus(const LineFilm& f) { return 2.0 * f.reduced_modulus; }

double speed_parameter(const LineFilm& f, double entrainment_speed) {
  return 2.0 * f.viscosity * entrainment_speed / (moes_modulus(f) * f.reduced_radius);
}

double material_parameter(const LineFilm& f, double speed_parameter) {
  return f.pressure_viscosity * moes_modulus(f) * std::pow(speed_parameter, 0.25);
}

double film_load_parameter(double film_parameter, double material_parameter, double* slope) {
  const double s = regime_blend_exponent, H = film_parameter;
  const double ivr = martin_load_constant / H;
  const double pve = material_parameter > 0 ? std::pow(material_parameter, 6) * std::pow(moes_pve_constant / H, 8) : 0.0;
  const double ivr_s = std::pow(ivr, s), pve_s = std::pow(pve, s);
  const double m = std::pow(ivr_s + pve_s, 1.0 / s);
  if (slope) *slope = -std::pow(m, 1.0 - s) * (ivr_s + 8.0 * pve_s) / H;
  return m;
}

double film_load_per_length(const LineFilm& f, double h, double u, double* d_thickness, double* d_speed) {
  double window_slope = 0;
  const double window = film_window(h, f.cutoff, &window_slope);
  const double ivr_per_speed = 2.0 * martin_load_constant * f.viscosity * f.reduced_radius / h;
  if (!(u > 0)) {  // no entrainment: no film load; the rigid-isoviscous slope in u
    if (d_thickness) *d_thickness = 0;
    if (d_speed) *d_speed = ivr_per_speed * window;
    return 0.0;
  }
  const double U = speed_parameter(f, u), root_u = std::sqrt(U);
  const double L = material_parameter(f, U);
  const double H = h / (f.reduced_radius * root_u);
  double dm_dh = 0;
  const double m = film_load_parameter(H, L, &dm_dh);
  const double scale = moes_modulus(f) * f.reduced_radius * root_u;  // w = scale M_1
  const double w = scale * m;
  if (d_thickness) *d_thickness = scale * dm_dh / (f.reduced_radius * root_u) * window + w * window_slope;
  if (d_speed) {
    // dM_1/dL at fixed H: only the PVE part depends on L (M_PVE ~ L^6).
    const double s = regime_blend_exponent;
    const double pve = L > 0 ? std::pow(L, 6) * std::pow(moes_pve_constant / H, 8) : 0.0;
    const double dm_dl = L > 0 ? std::pow(m, 1.0 - s) * std::pow(pve, s) * 6.0 / L : 0.0;
    // U ~ u, sqrt(U) ~ u^0.5, H ~ u^-0.5, L ~ u^0.25.
    *d_speed = (0.5 * w / u + scale * (dm_dh * (-0.5 * H / u) + dm_dl * 0.25 * L / u)) * window;
  }
  return w * window;
}

double film_thickness(const LineFilm& f, double load_per_length, double u) {
  LineFilm bare = f;
  bare.cutoff = 0;
  // Bisection on log h: the load falls monotonically with h.
  double lo = std::log(1e-12 * f.reduced_radius), hi = std::log(f.reduced_radius);
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (film_load_per_length(bare, std::exp(mid), u) > load_per_length ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

EhdState evaluate_ehd(const EhdLineLaw& law, double gap, double u) {
  EhdState st;
  const double n = palmgren_exponent, K = law.stiffness, len = law.film.length;
  if (!std::isfinite(gap) || !std::isfinite(u)) {
    st.valid = false;
    return st;
  }
  const double dry_deflection = std::max(0.0, -gap);
  const bool film = u > 0 && (law.film.cutoff <= 0 || gap < law.film.cutoff);
  if (!film) {  // dry Palmgren contact of the overlap
    st.deflection = dry_deflection;
    st.force = dry_deflection > 0 ? K * std::pow(dry_deflection, n) : 0.0;
    st.d_force_d_gap = dry_deflection > 0 ? -n * K * std::pow(dry_deflection, n - 1) : 0.0;
    st.valid = dry_deflection <= law.max_approach;
    return st;
  }
  // F(h) = K (h - gap)^n - len w(h) = 0 for h > max(gap, 0): F rises monotonically from < 0.
  const auto residual = [&](double h, double* slope) {
    double w_h = 0;
    const double w = film_load_per_length(law.film, h, u, &w_h);
    const double d = h - gap;
    if (slope) *slope = n * K * std::pow(d, n - 1) - len * w_h;
    return K * std::pow(d, n) - len * w;
  };
  double lo = std::max(gap, 0.0), hi = lo + std::max({std::abs(gap), 1e-9, 1e-6 * law.film.reduced_radius});
  for (int grow = 0; grow < 80 && residual(hi, nullptr) < 0; ++grow) hi = lo + 2 * (hi - lo);
  // Safeguarded Newton: a Newton step inside the bracket, else bisection.
  double h = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    double slope = 0;
    const double r = residual(h, &slope);
    (r < 0 ? lo : hi) = h;
    double next = h - r / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - h) <= 1e-15 * h || hi - lo <= 1e-16 * hi) {
      h = next;
      break;
    }
    h = next;
  }
  double w_h = 0, w_u = 0;
  const double w = film_load_per_length(law.film, h, u, &w_h, &w_u);
  const double d = std::max(h - gap, 0.0);
  const double elastic_slope = n * K * std::pow(d, n - 1);
  st.film_thickness = h;
  st.deflection = d;
  st.force = len * w;
  const double denominator = elastic_slope - len * w_h;  // > 0
  st.d_force_d_gap = len * w_h * elastic_slope / denominator;
  st.d_force_d_speed = len * w_h * (len * w_u / denominator) + len * w_u;
  const double U = speed_parameter(law.film, u);
  st.load_parameter = w / (moes_modulus(law.film) * law.film.reduced_radius * std::sqrt(U));
  st.valid = std::isfinite(st.force) && d <= law.max_approach;
  return st;
}

double poiseuille_force_per_length(const LineFilm& f, double U, double load_parameter) {
  return moes_modulus(f) * f.reduced_radius * std::pow(U, 0.75) *
         std::min(1.42 * std::sqrt(std::max(load_parameter, 0.0)), 1.47);
}

double CouetteTraction::coefficient(double slip_velocity, double entrainment_speed) const {
  if (friction_coefficient == 0) return 0;
  const double ratio = slip_velocity / std::hypot(entrainment_speed, speed_floor);
  return friction_coefficient * std::tanh(ratio / saturation_ratio);
}

HydrodynamicForce evaluate_hydrodynamic(const HydrodynamicLineLaw& law, double gap, double gap_rate, double u) {
  HydrodynamicForce out;
  if (!std::isfinite(gap) || !std::isfinite(gap_rate) || !std::isfinite(u)) {
    out.valid = false;
    return out;
  }
  const LineFilm& f = law.film;
  // Smooth maximum of the gap and the floor: the film never closes; the squeeze speed is the
  // surfaces' approach speed.
  const double floor = law.film_floor, root = std::hypot(gap - floor, floor);
  const double h = 0.5 * (gap + floor + root);
  const double h_rate = gap_rate;
  const double window = film_window(h, f.cutoff, nullptr);
  if (window > 0) {
    // Rolling and squeeze together, with cavitation (reynolds_line_film.hpp): not their sum.
    out.film_force =
        f.length * reynolds_line_load_per_length(f.viscosity, f.reduced_radius, h, u, h_rate) * window;
    // Couette shear of a rigid cylinder on a plane: eta u_s integral dx / h = eta u_s pi sqrt(2 R / h).
    out.couette_force_per_speed =
        f.length * f.viscosity * std::numbers::pi * std::sqrt(2.0 * f.reduced_radius / h) * window;
  }
  out.film_thickness = h;
  if (gap < 0) out.dry = evaluate_normal(law.dry, -gap, -gap_rate);
  out.force = out.film_force + out.dry.force;
  out.valid = out.dry.valid && std::isfinite(out.force);
  return out;
}

}  // namespace raceway::contact
