// The power balance of a model at one evaluation (docs/output_layout.md, "Power balance"): where the
// power that enters the bearing comes from and where it is dissipated, so that along any motion
//
//   d(stored energy)/dt = sum of inputs - sum of losses,
//
// the stored energy being Equations::energy without the applied loads' potential (kinetic, elastic
// contacts and springs, supports, gravity, the carrier frame's centrifugal potential, the nodes').
// Inputs:
//   drive      what holds the prescribed motions (a driven ring's spin, a prescribed tilt): minus the
//              contacts' power on the rings beyond what the rings' own states take up;
//   loads      the rings' applied loads on their free coordinates;
//   frame      the carrier frame's Euler force and moment and its centrifugal potential's change in time;
//   unbalance  the cage's unbalance force.
// Losses: each segment kind's `power_loss` (traction, damping, rolling resistance, films, drag, the
// internal springs' dampers), the supports' dampers, the nodes' own dampers (the housing's).
// Every term is a function of (t, z) and the segment records of the right-hand side at (t, z).
#pragma once

#include <string>
#include <vector>

#include "solver/bearing/equations.hpp"

namespace raceway::bearing {

class PowerTerms {
 public:
  static constexpr int input_count = 4;  // drive, loads, frame, unbalance
  static constexpr const char* input_names[input_count] = {"drive", "loads", "carrier_frame", "cage_unbalance"};

  explicit PowerTerms(const Model& m);
  /// The losses' names: the model's segment kinds in kind order, then "supports", then "nodes".
  const std::vector<std::string>& loss_names() const { return loss_names_; }
  /// Values per evaluation: the inputs, then the losses.
  std::size_t size() const { return static_cast<std::size_t>(input_count) + loss_names_.size(); }
  /// The terms [W] at (t, z): eq.rhs(t, z) must have just filled its records and contact loads.
  void evaluate(const Equations& eq, double t, const double* z, double* out) const;
  /// The stored energy [J] at (t, z) from Equations::energy(t, z) (`energy`).
  static double stored_energy(const Equations& eq, double t, const double* z, double energy);

 private:
  double drive(const Equations& eq, double t, const double* z) const;
  const Model& m_;
  std::vector<std::string> loss_names_;
  std::vector<int> loss_column_;  ///< per segment: its column among the losses
  std::vector<int> loss_field_;   ///< per segment: power_loss in its family's field table
};

}  // namespace raceway::bearing
