// raceway report: the metrics of a spatial run as summary.json (summarize_spatial_run of
// report.hpp; the metrics themselves are in cage_metrics.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "io/report/cage_metrics.hpp"
#include "io/report/report.hpp"

namespace raceway::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

std::vector<double> to_deg(const std::vector<double>& rad) {
  std::vector<double> out(rad.size());
  std::transform(rad.begin(), rad.end(), out.begin(), [](double v) { return v * kRadToDeg; });
  return out;
}

std::vector<double> column(const std::vector<double>& table, std::size_t row_size, std::size_t c) {
  std::vector<double> out(table.size() / row_size);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = table[i * row_size + c];
  return out;
}

// The members of a ContactStats in summary.json, in order; contact_time_s only in the totals.
struct ContactField {
  std::string_view key;
  double (*get)(const ContactStats&);
  bool per_pocket;
};
constexpr ContactField kContactFields[] = {
    {"rms_n", [](const ContactStats& c) { return c.rms; }, true},
    {"peak_n", [](const ContactStats& c) { return c.peak; }, true},
    {"impulse_n_s", [](const ContactStats& c) { return c.impulse; }, true},
    {"events", [](const ContactStats& c) { return static_cast<double>(c.events); }, true},
    {"contact_time_s", [](const ContactStats& c) { return c.contact_time; }, false},
    {"mean_duration_s", [](const ContactStats& c) { return c.mean_duration; }, true},
    {"duty_cycle", [](const ContactStats& c) { return c.duty_cycle; }, true},
};

// One bar's totals; the event count stays an integer.
JsonObject contact_json(const ContactStats& c) {
  JsonObject o;
  for (const ContactField& f : kContactFields) {
    if (f.key == "events")
      o.add("events", c.events);
    else
      o.add(std::string(f.key), f.get(c));
  }
  return o;
}

// One array per field, one value per pocket.
JsonObject per_pocket_json(const std::vector<ContactStats>& v) {
  JsonObject o;
  for (const ContactField& f : kContactFields) {
    if (!f.per_pocket) continue;
    std::vector<double> values;
    for (const auto& c : v) values.push_back(f.get(c));
    o.add(std::string(f.key), std::move(values));
  }
  return o;
}

// The summary under construction: its sections, the azimuth bins they share and the headlines.
struct Summary {
  const SpatialRun& run;
  TimeWindow window;
  double bin_width;  // rad
  JsonObject json;
  JsonObject azimuth_bins;
  bool azimuth_centres = false;
  std::vector<std::string> lines;

  void add_bins(const std::string& prefix, const AzimuthBins& b) {
    if (!azimuth_centres) azimuth_bins.add("bin_centre_deg", to_deg(b.centre)), azimuth_centres = true;
    azimuth_bins.add(prefix + "_mean_n", b.mean).add(prefix + "_max_n", b.max);
  }
  // Azimuth of ball k at sample i.
  double ball_azimuth(std::size_t i, std::size_t k) const {
    const double* p = run.ball_position.data() + (i * run.balls + k) * 3;
    return azimuth(p[0], p[1]);
  }
  // The columns of a segment kind that belong to balls, or nullptr without that kind.
  const SegmentColumns* ball_segments(const std::string& kind) const {
    const auto it = run.segments.find(kind);
    if (it == run.segments.end()) return nullptr;
    for (const int b : it->second.ball)
      if (b < 0) throw ReportInputError(fmt::format("report: '{}': '/segments/{}/ball' holds -1", run.path, kind));
    return &it->second;
  }
};

// Cage speed about the bearing axis (z) against the epicyclic and, if the file has it, the
// kinematic speed at the loaded contact angle. Returns the window statistics.
CageSpeedStats add_cage_speed(Summary& s) {
  const auto& t = s.run.time;
  const std::vector<double> omega_z = column(s.run.cage_angular_velocity, 3, 2);
  const CageSpeedStats cs = cage_speed_stats(t, omega_z, s.run.epicyclic_speed, s.window);
  JsonObject speed;
  speed.add("mean_rad_s", cs.cage_speed).add("mean_rpm", cs.cage_speed_rpm);
  speed.add("min_rad_s", cs.cage_speed_min).add("max_rad_s", cs.cage_speed_max);
  speed.add("epicyclic_rad_s", cs.epicyclic_speed).add("epicyclic_rpm", cs.epicyclic_speed_rpm);
  speed.add("slip", cs.slip).add("direction", cage_direction(cs.cage_speed));
  std::string rolling_line;
  if (!s.run.rolling_speed.empty()) {
    // Against the kinematic speed at the angle the balls actually roll at (under axial load a deep
    // groove bearing runs at 10-15 deg, not its nominal 0).
    const CageSpeedStats rs = cage_speed_stats(t, omega_z, s.run.rolling_speed, s.window);
    speed.add("rolling_rad_s", rs.epicyclic_speed).add("rolling_rpm", rs.epicyclic_speed_rpm).add("slip_rolling", rs.slip);
    rolling_line = fmt::format("kinematic cage speed at the loaded contact angle {:.2f} rpm: slip {:.3f} %",
                               rs.epicyclic_speed_rpm, 100 * rs.slip);
  }
  s.json.add("cage_speed", std::move(speed));
  s.lines.push_back(fmt::format("window {:.6g} .. {:.6g} s ({} samples): cage {:.2f} rpm, epicyclic {:.2f} rpm, "
                                "slip {:.3f} %",
                                s.window.t_begin, s.window.t_end, s.window.samples(), cs.cage_speed_rpm,
                                cs.epicyclic_speed_rpm, 100 * cs.slip));
  if (!rolling_line.empty()) s.lines.push_back(rolling_line);
  return cs;
}

// The cage centroid's trajectory: vortex radius, its ratio, sigma_v, whirl.
void add_centroid(Summary& s, double cage_speed) {
  const SpatialRun& run = s.run;
  const CentroidMetrics cm =
      centroid_metrics(run.time, column(run.cage_position, 3, 0), column(run.cage_position, 3, 1),
                       column(run.cage_velocity, 3, 0), column(run.cage_velocity, 3, 1), s.window, cage_speed);
  JsonObject cen;
  cen.add("centre_x_m", cm.centre_x).add("centre_y_m", cm.centre_y);
  cen.add("vortex_radius_mean_m", cm.radius_mean).add("vortex_radius_min_m", cm.radius_min);
  cen.add("vortex_radius_max_m", cm.radius_max).add("vortex_radius_ratio", cm.radius_ratio);
  cen.add("axis_radius_mean_m", cm.axis_radius_mean).add("axis_radius_min_m", cm.axis_radius_min);
  cen.add("axis_radius_max_m", cm.axis_radius_max).add("axis_radius_ratio", cm.axis_radius_ratio);
  cen.add("speed_mean_m_s", cm.speed_mean).add("speed_std_m_s", cm.speed_std).add("sigma_v", cm.sigma_v);
  cen.add("whirl_frequency_rad_s", cm.whirl_frequency).add("whirl_frequency_hz", cm.whirl_frequency_hz);
  cen.add("whirl_to_cage_speed_ratio", cm.whirl_to_cage_ratio).add("whirl_revolutions", cm.revolutions);
  cen.add("land_clearance_m", run.land_clearance).add("pocket_clearance_m", run.pocket_clearance);
  cen.add("pitch_radius_m", run.pitch_radius);
  s.json.add("cage_centroid", std::move(cen));
  s.lines.push_back(fmt::format("cage centroid: vortex radius {:.3g} um (ratio {:.3f}), sigma_v {:.3f}, whirl {:.3g} "
                                "rad/s = {:.3f} x cage speed",
                                1e6 * cm.radius_mean, cm.radius_ratio, cm.sigma_v, cm.whirl_frequency,
                                cm.whirl_to_cage_ratio));
}

// Pocket (bar) forces: front and rear totals, per pocket, and against the pocket's azimuth.
void add_pocket_forces(Summary& s, int direction, std::optional<double> contact_threshold) {
  const SegmentColumns* pc = s.ball_segments("ball_pocket");
  if (!pc) return;
  const std::size_t n = s.run.balls;
  const auto& fc = pc->diagnostic.at("circumferential_force");
  const BarForces bars = split_bar_forces(pc->diagnostic.at("normal_force"), fc, pc->ball, n, direction);
  const PocketForceSummary ps = pocket_force_summary(s.run.time, bars, fc, pc->ball, s.window, contact_threshold);
  JsonObject pf;
  pf.add("threshold_n", ps.threshold).add("direction", direction);
  pf.add("rear_impulse_fraction", ps.rear_impulse_fraction);
  pf.add("rms_circumferential_force_n", ps.rms_circumferential_force);
  pf.add("mean_net_circumferential_force_n", ps.mean_net_circumferential_force);
  pf.add("front", contact_json(ps.front_total)).add("rear", contact_json(ps.rear_total));
  pf.add("front_per_pocket", per_pocket_json(ps.front)).add("rear_per_pocket", per_pocket_json(ps.rear));
  s.json.add("pocket_forces", std::move(pf));
  s.lines.push_back(fmt::format("pocket forces (threshold {:.3g} N): front {} contacts, peak {:.3g} N; rear {} "
                                "contacts, peak {:.3g} N; rear impulse fraction {:.3f}",
                                ps.threshold, ps.front_total.events, ps.front_total.peak, ps.rear_total.events,
                                ps.rear_total.peak, ps.rear_impulse_fraction));

  std::vector<double> azs, front, rear;
  for (std::size_t i = s.window.begin; i < s.window.end; ++i)
    for (std::size_t k = 0; k < n; ++k) {
      azs.push_back(s.ball_azimuth(i, k));
      front.push_back(bars.front[k][i]);
      rear.push_back(bars.rear[k][i]);
    }
  s.add_bins("front_force", bin_by_azimuth(azs, front, s.bin_width));
  s.add_bins("rear_force", bin_by_azimuth(azs, rear, s.bin_width));
}

// Ball loads in the inner groove (all arcs of a ball added): the largest, binned over azimuth, and
// the load zone.
void add_ball_load(Summary& s) {
  const SegmentColumns* gc = s.ball_segments("ball_inner_groove");
  if (!gc) return;
  const std::size_t n = s.run.balls;
  const std::vector<double> load = ball_loads(gc->diagnostic.at("normal_force"), gc->ball, n);
  std::vector<double> azs, values;
  double qmax = -1, q_az = kNaN, q_t = kNaN;
  long long q_ball = -1;
  for (std::size_t i = s.window.begin; i < s.window.end; ++i)
    for (std::size_t k = 0; k < n; ++k) {
      const double q = load[i * n + k];
      azs.push_back(s.ball_azimuth(i, k));
      values.push_back(q);
      if (q > qmax) qmax = q, q_az = azs.back(), q_t = s.run.time[i], q_ball = static_cast<long long>(k);
    }
  const AzimuthBins bins = bin_by_azimuth(azs, values, s.bin_width);
  s.add_bins("ball_load", bins);
  double bin_peak = 0;
  for (const double m : bins.mean)
    if (std::isfinite(m)) bin_peak = std::max(bin_peak, m);
  const double zone_threshold = std::max(0.01 * bin_peak, 1e-3);
  const LoadZone z = load_zone(bins, zone_threshold);
  JsonObject bl;
  bl.add("max_n", qmax).add("max_azimuth_deg", q_az * kRadToDeg).add("max_time_s", q_t).add("max_ball", q_ball);
  bl.add("max_bin_mean_n", bin_peak).add("load_zone_threshold_n", zone_threshold);
  bl.add("load_zone_start_deg", z.start * kRadToDeg).add("load_zone_end_deg", z.end * kRadToDeg);
  bl.add("load_zone_width_deg", z.width * kRadToDeg).add("load_zone_centre_deg", z.centre * kRadToDeg);
  s.json.add("ball_load", std::move(bl));
  s.lines.push_back(fmt::format("inner-groove ball load: max {:.4g} N at {:.1f} deg; load zone {:.0f} deg wide "
                                "centred at {:.0f} deg",
                                qmax, q_az * kRadToDeg, z.width * kRadToDeg, z.centre * kRadToDeg));
}

// Power loss: time mean over the window of each kind's sum over its segments, and their total.
void add_power_loss(Summary& s) {
  const TimeWindow& w = s.window;
  JsonObject pl;
  double total = 0;
  const std::vector<double> wts = trapezoid_weights(s.run.time, w);
  for (const auto& [kind, cols] : s.run.segments) {
    const auto d = cols.diagnostic.find("power_loss");
    if (d == cols.diagnostic.end() || cols.columns() == 0) continue;
    double e = 0;
    for (std::size_t i = w.begin; i < w.end; ++i) {
      double row = 0;
      for (std::size_t c = 0; c < cols.columns(); ++c) row += d->second[i * cols.columns() + c];
      e += wts[i - w.begin] * row;
    }
    pl.add(kind + "_mean_w", e / w.length());
    total += e / w.length();
  }
  if (pl.empty()) return;
  pl.add("total_mean_w", total);
  s.json.add("power_loss", std::move(pl));
  s.lines.push_back(fmt::format("power loss: {:.4g} W (window mean)", total));
}

}  // namespace

JsonObject summarize_spatial_run(const SpatialRun& run, const ReportOptions& options,
                                 std::vector<std::string>* headlines) {
  if (!(options.bin_width_deg > 0 && options.bin_width_deg <= 360))
    throw std::invalid_argument(fmt::format("report: --bin-width {} deg is not in (0, 360]", options.bin_width_deg));
  Summary s{run, select_window(run.time, options.window_start), options.bin_width_deg / kRadToDeg, {}, {}, false, {}};
  s.json.add("report_format", 1LL).add("input", run.path).add("model_kind", "spatial").add("ball_count", run.balls);
  JsonObject win;
  win.add("start_s", s.window.t_begin).add("end_s", s.window.t_end).add("samples", s.window.samples());
  win.add("default_second_half", !options.window_start.has_value());
  s.json.add("window", std::move(win));

  const CageSpeedStats cs = add_cage_speed(s);
  add_centroid(s, cs.cage_speed);
  s.azimuth_bins.add("bin_width_deg", options.bin_width_deg);
  add_pocket_forces(s, cage_direction(cs.cage_speed), options.contact_threshold);
  add_ball_load(s);
  if (s.azimuth_centres) s.json.add("azimuth", std::move(s.azimuth_bins));
  add_power_loss(s);
  if (headlines) *headlines = std::move(s.lines);
  return std::move(s.json);
}

}  // namespace raceway::io
