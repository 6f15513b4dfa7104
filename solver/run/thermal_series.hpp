// The thermal network's series of the output (docs/output_layout.md, "Thermal network"): the
// temperatures, the heat into each part from the bearing's losses, the heat flow through each link,
// at each output time from the sample's right-hand side. Only with a [thermal] section.
#pragma once

#include <vector>

#include "io/h5/h5_series.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/thermal_network.hpp"

namespace raceway::run {

class ThermalSeries {
 public:
  /// Datasets and values per sample it adds for model m (OutputEstimate); 0 without a network.
  static int datasets(const bearing::Model& m);
  static long values(const bearing::Model& m);
  /// Defines the series when m has a thermal network.
  ThermalSeries(h5::H5SeriesWriter& file, const bearing::Model& m);
  /// Appends a sample: rhs at (t, z) has just filled the equations' records.
  void append(h5::H5SeriesWriter& file, const std::vector<double>& z, const bearing::Equations& eq);

 private:
  const bearing::ThermalNetwork* network_ = nullptr;
  h5::H5SeriesWriter::SeriesId temperature_ = 0, heat_ = 0, flow_ = 0;
  std::vector<double> row_;
};

}  // namespace raceway::run
