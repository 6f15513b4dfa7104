// raceway post-processing metrics (see cage_metrics.hpp for the definitions).
#include "io/report/cage_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace raceway::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kRadPerSToRpm = 60.0 / kTwoPi;

void require_size(std::span<const double> s, std::size_t n, const char* what) {
  if (s.size() != n)
    throw std::invalid_argument(std::string("cage metrics: ") + what + " has " + std::to_string(s.size()) +
                                " samples, expected " + std::to_string(n));
}

void require_window(std::span<const double> time, const TimeWindow& w) {
  if (w.end > time.size() || w.begin + 2 > w.end)
    throw std::invalid_argument("cage metrics: the window needs at least 2 samples within the series");
}

double ratio_or_nan(double num, double den) { return den != 0 && std::isfinite(den) ? num / den : kNaN; }

// Columns per row of a row-major [T x s] table with s = ball.size().
std::size_t rows_of(std::span<const double> table, std::span<const int> ball, const char* what) {
  if (ball.empty()) {
    if (!table.empty()) throw std::invalid_argument(std::string("cage metrics: ") + what + " has data but no columns");
    return 0;
  }
  if (table.size() % ball.size() != 0)
    throw std::invalid_argument(std::string("cage metrics: ") + what + " is not a [T x " +
                                std::to_string(ball.size()) + "] table");
  return table.size() / ball.size();
}

}  // namespace

// ---- time window -------------------------------------------------------------------------------

TimeWindow select_window(std::span<const double> time, std::optional<double> start) {
  if (time.size() < 2) throw std::invalid_argument("cage metrics: fewer than 2 output times");
  for (std::size_t i = 1; i < time.size(); ++i)
    if (!(time[i] > time[i - 1])) throw std::invalid_argument("cage metrics: output times are not increasing");
  const double t0 = time.front(), t1 = time.back();
  const double from = start ? *start : t0 + 0.5 * (t1 - t0);
  const double tol = 1e-9 * (t1 - t0);
  TimeWindow w;
  w.begin = static_cast<std::size_t>(std::lower_bound(time.begin(), time.end(), from - tol) - time.begin());
  w.end = time.size();
  if (w.samples() < 2)
    throw std::invalid_argument("cage metrics: fewer than 2 output times at or after the window start " +
                                std::to_string(from) + " s (run ends at " + std::to_string(t1) + " s)");
  w.t_begin = time[w.begin];
  w.t_end = time[w.end - 1];
  return w;
}

std::vector<double> trapezoid_weights(std::span<const double> time, const TimeWindow& window) {
  require_window(time, window);
  std::vector<double> w(window.samples(), 0.0);
  for (std::size_t i = window.begin; i + 1 < window.end; ++i) {
    const double h = 0.5 * (time[i + 1] - time[i]);
    w[i - window.begin] += h;
    w[i + 1 - window.begin] += h;
  }
  return w;
}

// ---- cage speed --------------------------------------------------------------------------------

CageSpeedStats cage_speed_stats(std::span<const double> time, std::span<const double> cage_speed,
                                std::span<const double> epicyclic_speed, const TimeWindow& window) {
  require_window(time, window);
  require_size(cage_speed, time.size(), "cage speed");
  require_size(epicyclic_speed, time.size(), "epicyclic speed");
  CageSpeedStats s;
  double sum_c = 0, sum_e = 0;
  s.cage_speed_min = std::numeric_limits<double>::infinity();
  s.cage_speed_max = -std::numeric_limits<double>::infinity();
  for (std::size_t i = window.begin; i < window.end; ++i) {
    sum_c += cage_speed[i];
    sum_e += epicyclic_speed[i];
    s.cage_speed_min = std::min(s.cage_speed_min, cage_speed[i]);
    s.cage_speed_max = std::max(s.cage_speed_max, cage_speed[i]);
  }
  const auto n = static_cast<double>(window.samples());
  s.cage_speed = sum_c / n;
  s.epicyclic_speed = sum_e / n;
  s.cage_speed_rpm = s.cage_speed * kRadPerSToRpm;
  s.epicyclic_speed_rpm = s.epicyclic_speed * kRadPerSToRpm;
  s.slip = s.epicyclic_speed != 0 ? 1.0 - s.cage_speed / s.epicyclic_speed : kNaN;
  return s;
}

// ---- cage centroid ------------------------------------------------------------------------------

CentroidMetrics centroid_metrics(std::span<const double> time, std::span<const double> x,
                                 std::span<const double> y, std::span<const double> vx,
                                 std::span<const double> vy, const TimeWindow& window,
                                 double cage_speed_mean) {
  require_window(time, window);
  require_size(x, time.size(), "cage x");
  require_size(y, time.size(), "cage y");
  require_size(vx, time.size(), "cage vx");
  require_size(vy, time.size(), "cage vy");
  const std::size_t b = window.begin, e = window.end;
  const auto n = static_cast<double>(window.samples());
  CentroidMetrics m;
  for (std::size_t i = b; i < e; ++i) m.centre_x += x[i], m.centre_y += y[i];
  m.centre_x /= n;
  m.centre_y /= n;

  auto radius_stats = [&](double cx, double cy, double& mean, double& lo, double& hi, double& ratio) {
    mean = 0;
    lo = std::numeric_limits<double>::infinity();
    hi = 0;
    for (std::size_t i = b; i < e; ++i) {
      const double r = std::hypot(x[i] - cx, y[i] - cy);
      mean += r;
      lo = std::min(lo, r);
      hi = std::max(hi, r);
    }
    mean /= n;
    ratio = ratio_or_nan(hi - lo, mean);
  };
  radius_stats(m.centre_x, m.centre_y, m.radius_mean, m.radius_min, m.radius_max, m.radius_ratio);
  radius_stats(0.0, 0.0, m.axis_radius_mean, m.axis_radius_min, m.axis_radius_max, m.axis_radius_ratio);

  // Speed: two passes (mean, then squared deviations) for accuracy.
  for (std::size_t i = b; i < e; ++i) m.speed_mean += std::hypot(vx[i], vy[i]);
  m.speed_mean /= n;
  double ss = 0;
  for (std::size_t i = b; i < e; ++i) {
    const double d = std::hypot(vx[i], vy[i]) - m.speed_mean;
    ss += d * d;
  }
  m.speed_std = std::sqrt(ss / (n - 1));
  m.sigma_v = ratio_or_nan(m.speed_std, m.speed_mean);

  // Whirl: unwrapped angle about the mean centre.
  double phi_prev = std::atan2(y[b] - m.centre_y, x[b] - m.centre_x), swept = 0;
  for (std::size_t i = b + 1; i < e; ++i) {
    const double phi = std::atan2(y[i] - m.centre_y, x[i] - m.centre_x);
    swept += std::remainder(phi - phi_prev, kTwoPi);  // step in (-pi, pi]
    phi_prev = phi;
  }
  // A centre that does not move (radii at the rounding level of its coordinates) has no whirl
  // radius ratio and no angle to follow.
  const double rounding = 64 * std::numeric_limits<double>::epsilon() * (std::abs(m.centre_x) + std::abs(m.centre_y));
  if (!(m.radius_max > rounding)) {
    m.radius_ratio = kNaN;
    swept = kNaN;
  }
  m.whirl_frequency = swept / window.length();
  m.whirl_frequency_hz = m.whirl_frequency / kTwoPi;
  m.whirl_to_cage_ratio = ratio_or_nan(m.whirl_frequency, cage_speed_mean);
  m.revolutions = swept / kTwoPi;
  return m;
}

// ---- pocket forces --------------------------------------------------------------------------------

int cage_direction(double cage_speed_mean) { return cage_speed_mean < 0 ? -1 : 1; }

BarForces split_bar_forces(std::span<const double> normal_force, std::span<const double> circumferential_force,
                           std::span<const int> ball, std::size_t pockets, int direction) {
  if (direction != 1 && direction != -1) throw std::invalid_argument("cage metrics: direction must be +1 or -1");
  const std::size_t s = ball.size();
  const std::size_t t = rows_of(normal_force, ball, "pocket normal force");
  if (circumferential_force.size() != normal_force.size())
    throw std::invalid_argument("cage metrics: pocket normal and circumferential force differ in size");
  for (const int k : ball)
    if (k < 0 || static_cast<std::size_t>(k) >= pockets)
      throw std::invalid_argument("cage metrics: pocket column with ball index " + std::to_string(k) +
                                  " outside [0, " + std::to_string(pockets) + ")");
  BarForces bars;
  bars.direction = direction;
  bars.front.assign(pockets, std::vector<double>(t, 0.0));
  bars.rear.assign(pockets, std::vector<double>(t, 0.0));
  for (std::size_t i = 0; i < t; ++i) {
    for (std::size_t c = 0; c < s; ++c) {
      const double fn = normal_force[i * s + c], fc = circumferential_force[i * s + c];
      if (!(fn > 0)) continue;
      const auto k = static_cast<std::size_t>(ball[c]);
      (fc * direction < 0 ? bars.front : bars.rear)[k][i] += fn;
    }
  }
  return bars;
}

ContactStats contact_stats(std::span<const double> time, std::span<const double> force, const TimeWindow& window,
                           double threshold) {
  require_size(force, time.size(), "bar force");
  const std::vector<double> w = trapezoid_weights(time, window);
  ContactStats c;
  double sq = 0;
  bool in_contact = false;
  for (std::size_t i = window.begin; i < window.end; ++i) {
    const double f = std::abs(force[i]), wi = w[i - window.begin];
    sq += wi * f * f;
    c.impulse += wi * f;
    c.peak = std::max(c.peak, f);
    const bool touching = f > threshold;
    if (touching) {
      c.contact_time += wi;
      if (!in_contact) ++c.events;
    }
    in_contact = touching;
  }
  const double len = window.length();
  c.rms = std::sqrt(sq / len);
  c.duty_cycle = c.contact_time / len;
  c.mean_duration = c.events > 0 ? c.contact_time / static_cast<double>(c.events) : kNaN;
  return c;
}

double default_contact_threshold(const BarForces& bars, const TimeWindow& window) {
  double peak = 0;
  for (const auto* side : {&bars.front, &bars.rear})
    for (const auto& f : *side)
      for (std::size_t i = window.begin; i < std::min(window.end, f.size()); ++i) peak = std::max(peak, std::abs(f[i]));
  return std::max(0.01 * peak, 1e-3);
}

PocketForceSummary pocket_force_summary(std::span<const double> time, const BarForces& bars,
                                        std::span<const double> circumferential_force, std::span<const int> ball,
                                        const TimeWindow& window, std::optional<double> threshold) {
  require_window(time, window);
  const std::size_t pockets = bars.front.size();
  if (bars.rear.size() != pockets) throw std::invalid_argument("cage metrics: front and rear bar counts differ");
  PocketForceSummary s;
  s.threshold = threshold ? *threshold : default_contact_threshold(bars, window);
  const double len = window.length();

  auto total = [&](const std::vector<ContactStats>& per, ContactStats& t) {
    double ms = 0;
    for (const auto& c : per) {
      t.events += c.events;
      t.impulse += c.impulse;
      t.contact_time += c.contact_time;
      t.peak = std::max(t.peak, c.peak);
      ms += c.rms * c.rms;
    }
    const double np = per.empty() ? kNaN : static_cast<double>(per.size());
    t.rms = std::sqrt(ms / np);
    t.duty_cycle = t.contact_time / (np * len);
    t.mean_duration = t.events > 0 ? t.contact_time / static_cast<double>(t.events) : kNaN;
  };
  for (std::size_t k = 0; k < pockets; ++k) {
    s.front.push_back(contact_stats(time, bars.front[k], window, s.threshold));
    s.rear.push_back(contact_stats(time, bars.rear[k], window, s.threshold));
  }
  total(s.front, s.front_total);
  total(s.rear, s.rear_total);
  s.rear_impulse_fraction = ratio_or_nan(s.rear_total.impulse, s.front_total.impulse + s.rear_total.impulse);

  // Circumferential force per pocket (columns of a pocket added), then RMS over pockets and time
  // and the time mean of the sum over pockets.
  const std::size_t cols = ball.size();
  const std::size_t t = rows_of(circumferential_force, ball, "pocket circumferential force");
  if (cols > 0 && t != time.size())
    throw std::invalid_argument("cage metrics: pocket circumferential force is not [T x s]");
  const std::vector<double> w = trapezoid_weights(time, window);
  std::vector<double> per_pocket(pockets);
  double sq = 0, net = 0;
  for (std::size_t i = window.begin; i < window.end; ++i) {
    std::fill(per_pocket.begin(), per_pocket.end(), 0.0);
    for (std::size_t c = 0; c < cols; ++c) {
      const auto k = static_cast<std::size_t>(ball[c]);
      if (k >= pockets) throw std::invalid_argument("cage metrics: pocket column outside the pockets");
      per_pocket[k] += circumferential_force[i * cols + c];
    }
    const double wi = w[i - window.begin];
    for (const double f : per_pocket) {
      sq += wi * f * f;
      net += wi * f;
    }
  }
  s.rms_circumferential_force = pockets > 0 ? std::sqrt(sq / (static_cast<double>(pockets) * len)) : kNaN;
  s.mean_net_circumferential_force = net / len;
  return s;
}

// ---- azimuth binning ------------------------------------------------------------------------------

double azimuth(double x, double y) {
  double a = std::atan2(y, x);
  if (a < 0) a += kTwoPi;
  return a >= kTwoPi ? 0.0 : a;  // atan2 of (-x, -0.0) rounds to 2 pi after the shift
}

double AzimuthBins::upper(std::size_t k) const { return k + 1 < lower.size() ? lower[k + 1] : kTwoPi; }

AzimuthBins bin_by_azimuth(std::span<const double> azimuth_rad, std::span<const double> value, double width) {
  if (!(width > 0) || width > kTwoPi * (1 + 1e-12))
    throw std::invalid_argument("cage metrics: azimuth bin width must be in (0, 360] deg");
  if (azimuth_rad.size() != value.size())
    throw std::invalid_argument("cage metrics: azimuths and values differ in size");
  // A width that divides 2 pi up to rounding gives exactly 2 pi / width bins.
  const double q = kTwoPi / width;
  const auto nbins = static_cast<std::size_t>(std::abs(q - std::round(q)) < 1e-9 * q ? std::round(q) : std::ceil(q));
  AzimuthBins b;
  b.width = width;
  b.lower.resize(nbins);
  for (std::size_t k = 0; k < nbins; ++k) b.lower[k] = static_cast<double>(k) * width;
  b.centre.resize(nbins);
  for (std::size_t k = 0; k < nbins; ++k) b.centre[k] = 0.5 * (b.lower[k] + b.upper(k));
  b.mean.assign(nbins, 0.0);
  b.max.assign(nbins, -std::numeric_limits<double>::infinity());
  b.count.assign(nbins, 0);
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!std::isfinite(value[i]) || !std::isfinite(azimuth_rad[i])) continue;
    double a = std::fmod(azimuth_rad[i], kTwoPi);
    if (a < 0) a += kTwoPi;
    auto k = static_cast<std::size_t>(a / width);
    k = std::min(k, nbins - 1);
    b.mean[k] += value[i];
    b.max[k] = std::max(b.max[k], value[i]);
    ++b.count[k];
  }
  for (std::size_t k = 0; k < nbins; ++k) {
    if (b.count[k] == 0) {
      b.mean[k] = kNaN;
      b.max[k] = kNaN;
    } else {
      b.mean[k] /= static_cast<double>(b.count[k]);
    }
  }
  return b;
}

LoadZone load_zone(const AzimuthBins& bins, double threshold) {
  const std::size_t n = bins.mean.size();
  LoadZone z{kNaN, kNaN, kNaN, kNaN};
  if (n == 0) return z;
  // Each bin is loaded, unloaded, or empty (no samples: a short run does not visit every azimuth).
  auto empty = [&](std::size_t k) { return bins.count[k % n] == 0 || std::isnan(bins.mean[k % n]); };
  auto loaded = [&](std::size_t k) { return !empty(k) && bins.mean[k % n] > threshold; };
  auto unloaded = [&](std::size_t k) { return !empty(k) && !loaded(k); };
  std::size_t n_loaded = 0, n_unloaded = 0;
  for (std::size_t k = 0; k < n; ++k) n_loaded += loaded(k) ? 1 : 0, n_unloaded += unloaded(k) ? 1 : 0;
  if (n_loaded == 0) return z;
  if (n_unloaded == 0) return {0.0, kTwoPi, kTwoPi, std::numbers::pi};
  // Runs of not-unloaded bins, each starting after an unloaded bin, trimmed to loaded bins at both
  // ends (empty bins inside a run do not break it); keep the widest.
  std::size_t best_first = 0, best_last = 0;
  double best_width = -1;
  for (std::size_t k = 0; k < n; ++k) {
    if (unloaded(k) || !unloaded(k + n - 1)) continue;
    std::size_t len = 0;
    while (len < n && !unloaded(k + len)) ++len;
    std::size_t first = k, last = k + len - 1;
    while (first <= last && !loaded(first)) ++first;
    while (last > first && !loaded(last)) --last;
    if (first > last || !loaded(first)) continue;
    double width = 0;
    for (std::size_t j = first; j <= last; ++j) width += bins.upper(j % n) - bins.lower[j % n];
    if (width > best_width) best_width = width, best_first = first % n, best_last = last % n;
  }
  z.start = bins.lower[best_first];
  z.end = bins.upper(best_last);
  if (z.end >= kTwoPi) z.end -= kTwoPi;
  z.width = best_width;
  z.centre = std::fmod(z.start + 0.5 * best_width, kTwoPi);
  return z;
}

std::vector<double> ball_loads(std::span<const double> normal_force, std::span<const int> ball, std::size_t balls) {
  const std::size_t s = ball.size();
  const std::size_t t = rows_of(normal_force, ball, "groove normal force");
  for (const int k : ball)
    if (k < 0 || static_cast<std::size_t>(k) >= balls)
      throw std::invalid_argument("cage metrics: groove column with ball index " + std::to_string(k) +
                                  " outside [0, " + std::to_string(balls) + ")");
  std::vector<double> out(t * balls, 0.0);
  for (std::size_t i = 0; i < t; ++i)
    for (std::size_t c = 0; c < s; ++c) out[i * balls + static_cast<std::size_t>(ball[c])] += normal_force[i * s + c];
  return out;
}

}  // namespace raceway::io
