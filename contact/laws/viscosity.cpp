#include "contact/laws/viscosity.hpp"

#include <cmath>

namespace raceway::contact {

namespace {
/// log10(log10(nu + 0.7)), nu in mm^2/s.
double walther_ordinate(double nu) { return std::log10(std::log10(1e6 * nu + 0.7)); }
}  // namespace

WaltherConstants walther_constants(double nu1, double t1, double nu2, double t2) {
  WaltherConstants w;
  w.b = (walther_ordinate(nu1) - walther_ordinate(nu2)) / (std::log10(t2) - std::log10(t1));
  w.a = walther_ordinate(nu1) + w.b * std::log10(t1);
  return w;
}

double walther_viscosity(const WaltherConstants& w, double t) {
  return 1e-6 * (std::pow(10.0, std::pow(10.0, w.a - w.b * std::log10(t))) - 0.7);
}

VogelConstants vogel_constants(double eta1, double t1, double eta2, double t2, double eta3, double t3) {
  // ln eta = ln a + b / (T - c): with y_i = ln eta_i, (y1 - y2) / (y2 - y3) = ((t2 - t1) (t3 - c)) / ((t3 - t2) (t1 - c)),
  // linear in c.
  const double y1 = std::log(eta1), y2 = std::log(eta2), y3 = std::log(eta3);
  const double r = (y1 - y2) / (y2 - y3) * (t3 - t2) / (t2 - t1);  // = (t3 - c) / (t1 - c)
  VogelConstants v;
  v.c = (t3 - r * t1) / (1.0 - r);
  v.b = (y1 - y2) / (1.0 / (t1 - v.c) - 1.0 / (t2 - v.c));
  v.a = std::exp(y1 - v.b / (t1 - v.c));
  return v;
}

double vogel_viscosity(const VogelConstants& v, double t) { return v.a * std::exp(v.b / (t - v.c)); }

double roelands_index(double eta0, double alpha) {
  return alpha * roelands_reference_pressure / std::log(eta0 / roelands_limit_viscosity);
}

double roelands_exponent(double eta0, double z, double p) {
  return std::log(eta0 / roelands_limit_viscosity) * (std::pow(1.0 + p / roelands_reference_pressure, z) - 1.0);
}

}  // namespace raceway::contact
