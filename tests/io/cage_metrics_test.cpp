// Tests of the post-processing metrics (io/report/cage_metrics.hpp) against closed forms: a circular and
// an elliptical cage whirl (seed 001 section 4, eq. 9), square-pulse bar forces, the front / rear
// sign convention of docs/output_layout.md, and a Hertzian cos^1.5 ball-load zone.
#include "io/report/cage_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace {

using namespace raceway::io;
constexpr double kPi = std::numbers::pi;

std::vector<double> uniform_time(std::size_t n, double dt, double t0 = 0) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = t0 + static_cast<double>(i) * dt;
  return t;
}

// Composite Simpson rule of f over [a, b] with m (even) intervals.
template <class F>
double simpson(F f, double a, double b, int m) {
  const double h = (b - a) / m;
  double s = f(a) + f(b);
  for (int i = 1; i < m; ++i) s += (i % 2 ? 4 : 2) * f(a + i * h);
  return s * h / 3;
}

// Cage centre on an ellipse x = cx + a cos(w t), y = cy + b sin(w t) (a = b: a circle). 2N samples
// with N per window (the default window is the second half) covering `periods` whole periods, so
// the window's sample mean of any harmonic vanishes to rounding.
struct Whirl {
  std::vector<double> t, x, y, vx, vy;
  Whirl(double a, double b, double w, double cx, double cy, std::size_t n_window, int periods) {
    const double period = 2 * kPi / std::abs(w);
    const double dt = periods * period / static_cast<double>(n_window);
    t = uniform_time(2 * n_window, dt);
    for (const double ti : t) {
      const double th = w * ti;
      x.push_back(cx + a * std::cos(th));
      y.push_back(cy + b * std::sin(th));
      vx.push_back(-a * w * std::sin(th));
      vy.push_back(b * w * std::cos(th));
    }
  }
};

// ---- window -----------------------------------------------------------------------------------------

TEST(CageMetricsWindow, DefaultIsSecondHalfAndWeightsSumToLength) {
  const auto t = uniform_time(101, 0.01);  // 0 .. 1 s
  const TimeWindow w = select_window(t);
  EXPECT_EQ(w.begin, 50u);
  EXPECT_EQ(w.end, 101u);
  EXPECT_DOUBLE_EQ(w.t_begin, 0.5);
  EXPECT_DOUBLE_EQ(w.t_end, 1.0);
  const auto wts = trapezoid_weights(t, w);
  double s = 0;
  for (const double v : wts) s += v;
  EXPECT_NEAR(s, w.length(), 1e-14);
  EXPECT_NEAR(wts.front(), 0.005, 1e-15);
  EXPECT_NEAR(wts[1], 0.01, 1e-15);

  const TimeWindow w2 = select_window(t, 0.8);
  EXPECT_EQ(w2.begin, 80u);
  EXPECT_THROW(select_window(t, 0.995), std::invalid_argument);  // one sample left
  EXPECT_THROW(select_window(std::vector<double>{0.0, 1.0, 1.0}), std::invalid_argument);
}

TEST(CageMetricsSpeed, MeansRpmAndSlip) {
  const auto t = uniform_time(11, 0.1);
  std::vector<double> cage(11), epi(11, 50.0);
  for (std::size_t i = 0; i < 11; ++i) cage[i] = i < 5 ? 0.0 : 45.0 + (i % 2 ? 1.0 : -1.0);  // window: i >= 5
  const TimeWindow w = select_window(t);
  const CageSpeedStats s = cage_speed_stats(t, cage, epi, w);
  // Window i = 5..10: 44, 46, 44, 46, 44, 46 -> mean 45.
  EXPECT_NEAR(s.cage_speed, 45.0, 1e-12);
  EXPECT_NEAR(s.cage_speed_rpm, 45.0 * 60 / (2 * kPi), 1e-10);
  EXPECT_NEAR(s.epicyclic_speed_rpm, 50.0 * 60 / (2 * kPi), 1e-10);
  EXPECT_NEAR(s.slip, 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(s.cage_speed_min, 44.0);
  EXPECT_DOUBLE_EQ(s.cage_speed_max, 46.0);
  const CageSpeedStats z = cage_speed_stats(t, cage, std::vector<double>(11, 0.0), w);
  EXPECT_TRUE(std::isnan(z.slip));
}

// ---- centroid ----------------------------------------------------------------------------------------

TEST(CageMetricsCentroid, CircularWhirlHasZeroRatiosAndExactFrequency) {
  const double r = 40e-6, w = 310.0, cx = 30e-6, cy = -50e-6;  // orbit offset from the axis
  const Whirl c(r, r, w, cx, cy, 400, 3);
  const TimeWindow win = select_window(c.t);
  ASSERT_EQ(win.samples(), 400u);
  const double cage_speed = 2 * w;
  const CentroidMetrics m = centroid_metrics(c.t, c.x, c.y, c.vx, c.vy, win, cage_speed);
  EXPECT_NEAR(m.centre_x, cx, 1e-15);
  EXPECT_NEAR(m.centre_y, cy, 1e-15);
  EXPECT_NEAR(m.radius_mean, r, 1e-15);
  EXPECT_NEAR(m.radius_ratio, 0.0, 1e-9);
  EXPECT_NEAR(m.sigma_v, 0.0, 1e-9);
  EXPECT_NEAR(m.speed_mean, r * w, 1e-12 * r * w);
  EXPECT_NEAR(m.whirl_frequency, w, 1e-9 * w);
  EXPECT_NEAR(m.whirl_frequency_hz, w / (2 * kPi), 1e-9 * w);
  EXPECT_NEAR(m.whirl_to_cage_ratio, 0.5, 1e-9);
  EXPECT_NEAR(m.revolutions, 3.0 * 399 / 400, 1e-9);
  // About the bearing axis: mean distance of a circle (radius r) from a point at distance d
  // outside it is 2 (d + r) / pi * E(2 sqrt(d r) / (d + r)).
  const double d = std::hypot(cx, cy);
  const double axis_mean = 2 * (d + r) / kPi * std::comp_ellint_2(2 * std::sqrt(d * r) / (d + r));
  EXPECT_NEAR(m.axis_radius_mean, axis_mean, 1e-9 * axis_mean);
  EXPECT_LE(m.axis_radius_max, d + r + 1e-15);
  EXPECT_GE(m.axis_radius_min, d - r - 1e-15);
  EXPECT_GT(m.axis_radius_ratio, 1.0);  // the offset orbit looks unstable about the axis
}

TEST(CageMetricsCentroid, ClockwiseWhirlHasNegativeFrequency) {
  const double r = 10e-6, w = -120.0;
  const Whirl c(r, r, w, 0, 0, 256, 2);
  const TimeWindow win = select_window(c.t);
  const CentroidMetrics m = centroid_metrics(c.t, c.x, c.y, c.vx, c.vy, win, -60.0);
  EXPECT_NEAR(m.whirl_frequency, w, 1e-9 * std::abs(w));
  EXPECT_NEAR(m.whirl_to_cage_ratio, 2.0, 1e-9);
}

TEST(CageMetricsCentroid, StationaryCentreHasNoWhirl) {
  const auto t = uniform_time(20, 1e-3);
  const std::vector<double> x(20, 7e-6), y(20, -3e-6), zero(20, 0.0);
  const CentroidMetrics m = centroid_metrics(t, x, y, zero, zero, select_window(t), 100.0);
  EXPECT_NEAR(m.radius_mean, 0.0, 1e-18);  // the mean of equal numbers need not be exact
  EXPECT_TRUE(std::isnan(m.radius_ratio));
  EXPECT_TRUE(std::isnan(m.sigma_v));
  EXPECT_TRUE(std::isnan(m.whirl_frequency));
  EXPECT_NEAR(m.axis_radius_mean, std::hypot(7e-6, 3e-6), 1e-20);
  EXPECT_DOUBLE_EQ(m.axis_radius_ratio, 0.0);
}

TEST(CageMetricsCentroid, EllipticalWhirlMatchesClosedForms) {
  const double a = 60e-6, b = 35e-6, w = 250.0;
  const std::size_t n = 800;
  const Whirl e(a, b, w, 5e-6, 12e-6, n, 2);
  const TimeWindow win = select_window(e.t);
  ASSERT_EQ(win.samples(), n);
  const CentroidMetrics m = centroid_metrics(e.t, e.x, e.y, e.vx, e.vy, win, 100.0);

  // Radius r(th) = sqrt(a^2 cos^2 + b^2 sin^2): max a, min b (both sampled: n is a multiple of 4),
  // mean (2 a / pi) E(k), k^2 = 1 - b^2 / a^2. (The near-circle approximation mean ~ (a + b) / 2
  // gives the ratio 2 (a - b) / (a + b).)
  const double k = std::sqrt(1 - b * b / (a * a));
  const double mean_r = 2 * a / kPi * std::comp_ellint_2(k);
  EXPECT_NEAR(m.radius_mean, mean_r, 1e-10 * mean_r);
  EXPECT_NEAR(m.radius_max, a, 1e-15);
  EXPECT_NEAR(m.radius_min, b, 1e-15);
  EXPECT_NEAR(m.radius_ratio, (a - b) / mean_r, 1e-9);
  EXPECT_NEAR(m.radius_ratio, 2 * (a - b) / (a + b), 0.02);

  // Speed v(th) = w sqrt(a^2 sin^2 + b^2 cos^2) over uniform th: mean and mean square by quadrature.
  auto v = [&](double th) {
    return w * std::sqrt(a * a * std::sin(th) * std::sin(th) + b * b * std::cos(th) * std::cos(th));
  };
  const double ev = simpson(v, 0, 2 * kPi, 20000) / (2 * kPi);
  const double ev2 = simpson([&](double th) { return v(th) * v(th); }, 0, 2 * kPi, 20000) / (2 * kPi);
  EXPECT_NEAR(ev, w * mean_r, 1e-10 * w * mean_r);  // the same elliptic integral
  EXPECT_NEAR(ev2, w * w * (a * a + b * b) / 2, 1e-10 * ev2);
  const double sigma_population = std::sqrt(ev2 - ev * ev) / ev;
  const double nd = static_cast<double>(n);
  const double sigma_sample = sigma_population * std::sqrt(nd / (nd - 1));  // eq. 9 divides by n - 1
  EXPECT_NEAR(m.speed_mean, ev, 1e-10 * ev);
  EXPECT_NEAR(m.sigma_v, sigma_sample, 1e-8);
  EXPECT_GT(m.sigma_v, 0.1);  // about 0.18 for b / a = 0.58

  // Whirl: the angle about the centre turns once per period; the window's last sample is one step
  // short of a whole number of periods, so the estimate is within a step's angle error.
  EXPECT_NEAR(m.whirl_frequency, w, 0.01 * w);
}

// ---- pocket forces ---------------------------------------------------------------------------------

// Square pulses: height f, `on` samples long, one every `period` samples, first at `first`.
std::vector<double> pulse_train(std::size_t n, std::size_t first, std::size_t on, std::size_t period, double f,
                                double floor = 0) {
  std::vector<double> v(n, floor);
  for (std::size_t s = first; s < n; s += period)
    for (std::size_t i = s; i < std::min(n, s + on); ++i) v[i] = f;
  return v;
}

TEST(CageMetricsPockets, SquarePulsesGiveExactStatistics) {
  const double dt = 1e-4, f = 50.0;
  const std::size_t n = 1000, on = 7, period = 40;
  const auto t = uniform_time(n, dt);
  const TimeWindow w = select_window(t);  // samples 500 .. 999, 0.0499 s long
  ASSERT_EQ(w.begin, 500u);
  // First pulse of the window at 505 (pulses at 25 + 40 j); the last at 985 .. 991: 13 in the window.
  const auto force = pulse_train(n, 25, on, period, f);
  const ContactStats c = contact_stats(t, force, w, 0.5);
  const double len = w.length();
  const std::size_t events = 13;
  const double contact = static_cast<double>(events * on) * dt;
  EXPECT_NEAR(len, 499 * dt, 1e-15);
  EXPECT_EQ(c.events, events);
  EXPECT_NEAR(c.contact_time, contact, 1e-15);
  EXPECT_NEAR(c.mean_duration, on * dt, 1e-15);
  EXPECT_NEAR(c.duty_cycle, contact / len, 1e-12);
  EXPECT_NEAR(c.impulse, f * contact, 1e-12);
  EXPECT_NEAR(c.rms, f * std::sqrt(contact / len), 1e-10);
  EXPECT_DOUBLE_EQ(c.peak, f);

  // A floor below the threshold adds to the impulse and RMS but not to the contacts.
  const double floor = 0.2;
  const auto noisy = pulse_train(n, 25, on, period, f, floor);
  const ContactStats d = contact_stats(t, noisy, w, 0.5);
  EXPECT_EQ(d.events, events);
  EXPECT_NEAR(d.contact_time, contact, 1e-15);
  EXPECT_NEAR(d.impulse, f * contact + floor * (len - contact), 1e-12);
  EXPECT_NEAR(d.rms, std::sqrt((f * f * contact + floor * floor * (len - contact)) / len), 1e-10);

  // A contact going on when the window opens counts as one event (here half a sample's weight).
  const auto early = pulse_train(n, 497, on, period, f);  // 497 .. 503, then 537 ..
  const ContactStats e = contact_stats(t, early, w, 0.5);
  EXPECT_EQ(e.events, 13u);  // 497 (cut), 537, ..., 977
  EXPECT_NEAR(e.contact_time, (4 - 0.5) * dt + 12 * on * dt, 1e-15);
}

TEST(CageMetricsPockets, DefaultThresholdIsOnePercentOfPeakAtLeastAMilliNewton) {
  const auto t = uniform_time(10, 0.1);
  const TimeWindow w = select_window(t);
  BarForces bars;
  bars.front = {std::vector<double>(10, 0.0), std::vector<double>(10, 0.0)};
  bars.rear = bars.front;
  bars.rear[1][8] = 250.0;
  bars.front[0][2] = 900.0;  // before the window: ignored
  EXPECT_DOUBLE_EQ(default_contact_threshold(bars, w), 2.5);
  bars.rear[1][8] = 0.05;
  EXPECT_DOUBLE_EQ(default_contact_threshold(bars, w), 1e-3);
}

TEST(CageMetricsPockets, SignConventionFollowsCageDirection) {
  // Two pockets, one column each: pocket 0 has a negative circumferential force (the cage pushes
  // the ball back), pocket 1 a positive one; then both in one pocket on alternate samples.
  const std::size_t n = 4;
  const std::vector<int> ball = {0, 1};
  std::vector<double> fn, fc;
  for (std::size_t i = 0; i < n; ++i) {
    fn.insert(fn.end(), {10.0, 5.0});
    fc.insert(fc.end(), {-10.0, 5.0});
  }
  EXPECT_EQ(cage_direction(12.0), 1);
  EXPECT_EQ(cage_direction(-12.0), -1);
  const BarForces pos = split_bar_forces(fn, fc, ball, 2, cage_direction(12.0));
  EXPECT_DOUBLE_EQ(pos.front[0][1], 10.0);  // ball presses on the bar ahead: front
  EXPECT_DOUBLE_EQ(pos.rear[0][1], 0.0);
  EXPECT_DOUBLE_EQ(pos.rear[1][1], 5.0);    // the bar behind pushes the ball: rear
  EXPECT_DOUBLE_EQ(pos.front[1][1], 0.0);
  const BarForces neg = split_bar_forces(fn, fc, ball, 2, cage_direction(-12.0));
  EXPECT_DOUBLE_EQ(neg.rear[0][1], 10.0);
  EXPECT_DOUBLE_EQ(neg.front[0][1], 0.0);
  EXPECT_DOUBLE_EQ(neg.front[1][1], 5.0);
  EXPECT_DOUBLE_EQ(neg.rear[1][1], 0.0);

  const auto t = uniform_time(n, 1.0);
  const TimeWindow w{0, n, 0.0, 3.0};
  const PocketForceSummary sp = pocket_force_summary(t, pos, fc, ball, w);
  EXPECT_NEAR(sp.rear_impulse_fraction, 5.0 / 15.0, 1e-14);
  EXPECT_NEAR(sp.front_total.impulse, 30.0, 1e-12);
  EXPECT_NEAR(sp.rms_circumferential_force, std::sqrt((100.0 + 25.0) / 2), 1e-12);
  EXPECT_NEAR(sp.mean_net_circumferential_force, -5.0, 1e-12);
  const PocketForceSummary sn = pocket_force_summary(t, neg, fc, ball, w);
  EXPECT_NEAR(sn.rear_impulse_fraction, 10.0 / 15.0, 1e-14);

  // Zero normal force puts nothing on either bar, whatever the sign; bad ball indices throw.
  const BarForces none =
      split_bar_forces(std::vector<double>{0.0}, std::vector<double>{-3.0}, std::vector<int>{0}, 1, 1);
  EXPECT_DOUBLE_EQ(none.front[0][0] + none.rear[0][0], 0.0);
  EXPECT_THROW(split_bar_forces(fn, fc, std::vector<int>{0, 2}, 2, 1), std::invalid_argument);
}

TEST(CageMetricsPockets, SummaryTotalsOverPockets) {
  const double dt = 1e-3;
  const std::size_t n = 200;
  const auto t = uniform_time(n, dt);
  const TimeWindow w = select_window(t);  // 100 .. 199
  BarForces bars;
  bars.front = {pulse_train(n, 110, 5, 50, 20.0), std::vector<double>(n, 0.0)};
  bars.rear = {std::vector<double>(n, 0.0), pulse_train(n, 120, 10, 40, 40.0)};
  const std::vector<int> ball;  // no circumferential columns needed for the bar statistics
  const PocketForceSummary s = pocket_force_summary(t, bars, std::vector<double>{}, ball, w);
  EXPECT_DOUBLE_EQ(s.threshold, 0.4);
  EXPECT_EQ(s.front[0].events, 2u);  // 110, 160
  EXPECT_EQ(s.rear[1].events, 2u);   // 120, 160
  EXPECT_EQ(s.front_total.events, 2u);
  EXPECT_NEAR(s.front_total.impulse, 2 * 5 * dt * 20.0, 1e-12);
  EXPECT_NEAR(s.rear_total.impulse, 2 * 10 * dt * 40.0, 1e-12);
  EXPECT_NEAR(s.rear_impulse_fraction, 0.8 / 1.0, 1e-12);
  EXPECT_NEAR(s.rear_total.mean_duration, 10 * dt, 1e-15);
}

// ---- azimuth -------------------------------------------------------------------------------------------

TEST(CageMetricsAzimuth, AzimuthRangeAndBinEdges) {
  EXPECT_DOUBLE_EQ(azimuth(1, 0), 0.0);
  EXPECT_NEAR(azimuth(0, -1), 1.5 * kPi, 1e-15);
  EXPECT_NEAR(azimuth(-1, -1e-300), kPi, 1e-15);
  EXPECT_LT(azimuth(-1, -0.0), 2 * kPi);
  const double deg = kPi / 180;
  const AzimuthBins b = bin_by_azimuth(std::vector<double>{-1 * deg, 361 * deg, 3 * deg, 1e9},
                                       std::vector<double>{2.0, 4.0, 6.0, std::nan("")}, 7 * deg);
  ASSERT_EQ(b.mean.size(), 52u);  // 51 whole 7-degree bins and a 3-degree one
  EXPECT_NEAR(b.upper(51), 2 * kPi, 1e-15);
  EXPECT_NEAR(b.upper(51) - b.lower[51], 3 * deg, 1e-12);
  EXPECT_EQ(b.count[0], 2u);  // 361 and 3 deg
  EXPECT_DOUBLE_EQ(b.mean[0], 5.0);
  EXPECT_DOUBLE_EQ(b.max[0], 6.0);
  EXPECT_EQ(b.count[51], 1u);  // -1 deg = 359 deg
  EXPECT_TRUE(std::isnan(b.mean[20]));
  EXPECT_EQ(bin_by_azimuth(std::vector<double>{}, std::vector<double>{}, 5 * deg).mean.size(), 72u);
  EXPECT_THROW(bin_by_azimuth(std::vector<double>{}, std::vector<double>{}, 0.0), std::invalid_argument);
  EXPECT_THROW(bin_by_azimuth(std::vector<double>{}, std::vector<double>{}, 361 * deg), std::invalid_argument);
}

// Hertzian load zone with zero clearance: Q = Qmax cos^1.5(psi - psi0) within 90 deg of psi0.
// gap_deg > 0: no samples within gap_deg of psi0 + 45 deg and psi0 + 200 deg (bins left empty, as
// in a short run), which must neither split the zone nor join it to anything.
void check_cos15_zone(double psi0_deg, double gap_deg = 0) {
  const double deg = kPi / 180, qmax = 1800.0, psi0 = psi0_deg * deg;
  auto q = [&](double psi) {
    const double c = std::cos(psi - psi0);
    return c > 0 ? qmax * std::pow(c, 1.5) : 0.0;
  };
  // 9 balls turning through 4000 steps each (dense, uniform azimuths).
  std::vector<double> az, load;
  for (int i = 0; i < 4000; ++i)
    for (int k = 0; k < 9; ++k) {
      const double psi = 2 * kPi * (k / 9.0 + (i + 0.5) / 36000.0);
      auto near_deg = [&](double c) {
        return std::abs(std::remainder(psi - (psi0_deg + c) * deg, 2 * kPi)) < gap_deg * deg;
      };
      if (near_deg(45) || near_deg(200)) continue;
      az.push_back(psi);
      load.push_back(q(psi));
    }
  const AzimuthBins b = bin_by_azimuth(az, load, 5 * deg);
  ASSERT_EQ(b.mean.size(), 72u);
  double max_of_max = 0, max_mean = 0;
  std::size_t empty_bins = 0;
  for (std::size_t k = 0; k < 72; ++k) {
    if (b.count[k] == 0) {
      ++empty_bins;
      continue;
    }
    max_of_max = std::max(max_of_max, b.max[k]);
    max_mean = std::max(max_mean, b.mean[k]);
    if (gap_deg > 0) continue;
    ASSERT_EQ(b.count[k], 500u);
    // Bin mean = the distribution's mean over the bin.
    const double exact = simpson([&](double p) { return q(p); }, b.lower[k], b.upper(k), 200) / (5 * deg);
    EXPECT_NEAR(b.mean[k], exact, 2e-3 * qmax) << "bin " << k;
  }
  EXPECT_NEAR(max_of_max, qmax, 1e-7 * qmax);  // a sample within 0.005 deg of psi0
  EXPECT_EQ(empty_bins, gap_deg > 0 ? 8u : 0u);
  const LoadZone z = load_zone(b, 0.01 * max_mean);
  // The zone is 180 deg wide around psi0: edges within one bin of psi0 -/+ 90 deg.
  auto ang_diff = [&](double x, double y) { return std::abs(std::remainder(x - y, 2 * kPi)); };
  EXPECT_LE(ang_diff(z.start, psi0 - kPi / 2), 5 * deg + 1e-9);
  EXPECT_LE(ang_diff(z.end, psi0 + kPi / 2), 5 * deg + 1e-9);
  EXPECT_NEAR(z.width, kPi, 10 * deg + 1e-9);
  EXPECT_LE(ang_diff(z.centre, psi0), 2.5 * deg + 1e-9);
}

TEST(CageMetricsAzimuth, Cos15LoadZoneAtTheBottom) { check_cos15_zone(270); }
TEST(CageMetricsAzimuth, Cos15LoadZoneWrappingThroughZero) { check_cos15_zone(10); }
TEST(CageMetricsAzimuth, Cos15LoadZoneWithEmptyBins) {
  check_cos15_zone(270, 12);
  check_cos15_zone(10, 12);
}

TEST(CageMetricsAzimuth, LoadZoneAllOrNothing) {
  const double deg = kPi / 180;
  AzimuthBins b = bin_by_azimuth(std::vector<double>{0.1, 1, 2, 3, 4, 5, 6}, std::vector<double>(7, 3.0), 60 * deg);
  LoadZone z = load_zone(b, 1.0);
  EXPECT_NEAR(z.width, 2 * kPi, 1e-12);
  z = load_zone(b, 5.0);
  EXPECT_TRUE(std::isnan(z.start));
  EXPECT_TRUE(std::isnan(z.width));
}

TEST(CageMetricsAzimuth, BallLoadsAddArcs) {
  // Four-point bearing: two arcs per ball, columns 0a 0b 1a 1b; two times.
  const std::vector<int> ball = {0, 0, 1, 1};
  const std::vector<double> fn = {1, 2, 3, 4, 5, 6, 7, 8};
  const auto q = ball_loads(fn, ball, 2);
  ASSERT_EQ(q.size(), 4u);
  EXPECT_DOUBLE_EQ(q[0], 3.0);
  EXPECT_DOUBLE_EQ(q[1], 7.0);
  EXPECT_DOUBLE_EQ(q[2], 11.0);
  EXPECT_DOUBLE_EQ(q[3], 15.0);
  EXPECT_THROW(ball_loads(fn, std::vector<int>{0, 0, 1}, 2), std::invalid_argument);
  EXPECT_THROW(ball_loads(fn, std::vector<int>{0, 0, 1, 2}, 2), std::invalid_argument);
}

}  // namespace
