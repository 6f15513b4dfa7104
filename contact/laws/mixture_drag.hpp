// Drag and churning in the oil-air mixture that fills a bearing's cavity: pure functions, SI inside.
//
// The mixture (Harris & Kotzalas, vol. 2, the fluid drag on the balls of a high-speed bearing): a
// fraction X of the cavity's volume is oil, the rest air, and the mixture's effective density is
// X rho_oil, air's own density neglected (about 1/700 of an oil's). The effective viscosity is raceway's
// assumption, the same volume weighting, X eta_oil; the kinematic viscosity, which sets the Reynolds
// number, is then the oil's. X = 0: no mixture, no drag.
//
// A sphere of diameter d moving at v relative to the mixture feels the drag
//   F = 0.5 rho_e C_D(Re) (pi d^2 / 4) |v| v,  Re = rho_e |v| d / eta_e,
// opposite v, with Schiller and Naumann's correlation C_D = 24/Re (1 + 0.15 Re^0.687), written for
// Re <= 1000, and Newton's regime C_D = 0.44 above (as Clift, Grace & Weber give them). Taken as
// max(Schiller-Naumann, 0.44), which is continuous (the two meet at Re = 989) and tends to Stokes'
// F = 3 pi eta d v as Re -> 0. Valid below the drag crisis (Re about 2e5).
//
// A ring (the cage) turning at omega relative to the mixture: each of its two annular faces feels
// von Karman's laminar wall shear of a disc turning in a fluid at rest, tau = 0.616 rho r sqrt(nu omega^3)
// (von Karman's similarity solution, as Schlichting & Gersten give it; on both faces of a full disc of radius r it gives the moment
// 0.5 rho omega^2 r^5 C_M with C_M = 3.87 Re^-1/2, Re = omega r^2 / nu), integrated over the annulus
// between its bore and outside radii: per face
//   M = (pi / 2) 0.616 rho sqrt(nu) |omega|^(3/2) (r_o^4 - r_i^4),
// opposite omega. Valid while the boundary layer is laminar, Re < about 3e5, and the faces far from the
// rings' (an unconfined disc). The ring's cylindrical surfaces and the pockets are left out, so it is
// a lower bound of the cage's churning moment.
// Closed forms, a few lines each: no Debian package has them.
#pragma once

#include <Eigen/Dense>

namespace raceway::contact {

/// The effective oil-air mixture (see above): density [kg/m^3] and viscosity [Pa s].
struct OilAirMixture {
  double density = 0;
  double viscosity = 0;
  bool present() const { return density > 0 && viscosity > 0; }
};
/// The mixture of an oil (density, dynamic viscosity) at a volume fraction X in [0, 1].
OilAirMixture oil_air_mixture(double oil_density, double oil_viscosity, double oil_volume_fraction);

/// Sphere drag coefficient C_D(Re): max(Schiller-Naumann, 0.44); Re > 0.
double sphere_drag_coefficient(double reynolds);

/// The drag on a sphere moving at `relative_velocity` through the mixture.
struct SphereDrag {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< N, on the sphere, opposite the relative velocity
  double reynolds = 0;
  double drag_coefficient = 0;
  double power_loss = 0;  ///< W, -force . relative_velocity >= 0
};
SphereDrag sphere_drag(const OilAirMixture& mixture, double diameter, const Eigen::Vector3d& relative_velocity);

/// Von Karman's laminar moment about the axis on the two faces of an annulus (radii r_inner < r_outer)
/// turning at `relative_spin` [rad/s] in the mixture [N m], opposite the spin.
double ring_churning_moment(const OilAirMixture& mixture, double r_inner, double r_outer, double relative_spin);

}  // namespace raceway::contact
