#include "solver/run/thermal_series.hpp"

#include <string>

namespace raceway::run {

using bearing::ThermalNetwork;

int ThermalSeries::datasets(const bearing::Model& m) { return bearing::thermal_network_of(m) ? 3 : 0; }

long ThermalSeries::values(const bearing::Model& m) {
  const ThermalNetwork* n = bearing::thermal_network_of(m);
  return n ? 2 * ThermalNetwork::parts + static_cast<long>(n->links().size()) : 0;
}

ThermalSeries::ThermalSeries(h5::H5SeriesWriter& file, const bearing::Model& m) : network_(bearing::thermal_network_of(m)) {
  if (!network_) return;
  const std::vector<std::string> parts(std::begin(ThermalNetwork::part_names), std::end(ThermalNetwork::part_names));
  std::vector<std::string> links;
  for (const ThermalNetwork::Link& l : network_->links()) links.push_back(l.name);
  file.define_series("/thermal/temperature", {ThermalNetwork::parts}, "K", "temperature of each part of the network");
  file.define_series("/thermal/heat_input", {ThermalNetwork::parts}, "W",
                     "heat into each part from the bearing's losses (each segment's power_loss, half to each of its "
                     "bodies; drag and churning to the oil)");
  file.define_series("/thermal/link_flow", {links.size()}, "W",
                     "heat flow through each link, from its first part to its second (the ambient: the shaft, the air)");
  file.set_attribute("/thermal/temperature", "components", parts);
  file.set_attribute("/thermal/heat_input", "components", parts);
  file.set_attribute("/thermal/link_flow", "components", links);
  file.set_attribute("/thermal", "ambient_temperature", network_->ambient_temperature());
  file.set_attribute("/thermal", "heat_capacity", std::vector<double>(network_->capacity().begin(), network_->capacity().end()));
  std::vector<double> conductance;
  for (const ThermalNetwork::Link& l : network_->links()) conductance.push_back(l.conductance);
  file.set_attribute("/thermal", "link_conductance", conductance);
  temperature_ = file.series_id("/thermal/temperature");
  heat_ = file.series_id("/thermal/heat_input");
  flow_ = file.series_id("/thermal/link_flow");
}

void ThermalSeries::append(h5::H5SeriesWriter& file, const std::vector<double>& z, const bearing::Equations& eq) {
  if (!network_) return;
  row_.resize(ThermalNetwork::parts);
  for (int k = 0; k < ThermalNetwork::parts; ++k) row_[static_cast<std::size_t>(k)] = z[static_cast<std::size_t>(network_->state(k))];
  file.append(temperature_, row_);
  network_->heat_inputs(eq.segment_records().data(), row_.data());
  file.append(heat_, row_);
  row_.resize(network_->links().size());
  network_->link_flows(z.data(), row_.data());
  file.append(flow_, row_);
}

}  // namespace raceway::run
