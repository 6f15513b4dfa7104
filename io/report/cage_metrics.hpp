// raceway post-processing: cage and ball metrics computed from output time series
// (`raceway report`, io/report/report.hpp).
//
// Pure functions on in-memory series: no HDF5, no files, no physics model. All quantities are SI
// (s, m, m/s, rad, rad/s, N, N s) unless a name says otherwise (`_rpm`, `_deg`).
//
// Time averages and integrals over a window use the trapezoid rule. Its weights w_i (half the
// sum of the two intervals next to sample i, half an interval at the window's ends, summing to
// the window length) are used for every time-based quantity, so they are mutually consistent:
//   impulse = sum_i w_i |F_i|,  contact time = sum_{i in contact} w_i,
//   RMS = sqrt(sum_i w_i F_i^2 / window length),  duty cycle = contact time / window length.
// For a sampled square pulse of height F lasting k samples (zeros on both sides), this gives an
// impulse F k dt and a duration k dt exactly: each sample stands for one interval dt.
//
// Plain means (cage speed, centroid statistics) are sample means, like the run summary's
// `cage_speed_rpm` (solver/run/run.cpp), because output times are equally spaced.
//
// Functions return NaN for quantities that are undefined on the given data (a zero mean
// speed, an empty bin, no contact at all); they throw std::invalid_argument for inconsistent
// inputs (different lengths, an empty window, a bin width outside (0, 360] deg).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace raceway::io {

// ---- time window -------------------------------------------------------------------------------

/// Samples [begin, end) of a time series that form the analysis window.
struct TimeWindow {
  std::size_t begin = 0;
  std::size_t end = 0;  ///< one past the last sample
  double t_begin = 0;   ///< s, time of sample begin
  double t_end = 0;     ///< s, time of sample end - 1
  std::size_t samples() const { return end - begin; }
  double length() const { return t_end - t_begin; }
};

/// The samples with time >= start (start given) or, by default, the second half of the run:
/// time >= t_0 + (t_last - t_0) / 2 (the run summary's "second half", solver/run/run.cpp). A
/// tolerance of 1e-9 of the run length keeps a sample that sits on the boundary. Throws
/// std::invalid_argument if time is empty, not increasing, or fewer than 2 samples fall in the
/// window.
TimeWindow select_window(std::span<const double> time, std::optional<double> start = std::nullopt);

/// Trapezoid weights of the window's samples (size window.samples(); they sum to window.length()).
std::vector<double> trapezoid_weights(std::span<const double> time, const TimeWindow& window);

// ---- cage speed --------------------------------------------------------------------------------

struct CageSpeedStats {
  double cage_speed = 0;           ///< rad/s, mean over the window
  double cage_speed_rpm = 0;
  double epicyclic_speed = 0;      ///< rad/s, mean kinematic (epicyclic) cage speed, same samples
  double epicyclic_speed_rpm = 0;
  double slip = 0;                 ///< 1 - cage / epicyclic; NaN if the epicyclic speed is 0
  double cage_speed_min = 0;       ///< rad/s, extremes over the window (speed fluctuation)
  double cage_speed_max = 0;
};

/// Sample means of the cage speed (rotation rate about the bearing axis) and of the epicyclic
/// speed over the window. Both series have the size of time.
CageSpeedStats cage_speed_stats(std::span<const double> time, std::span<const double> cage_speed,
                                std::span<const double> epicyclic_speed, const TimeWindow& window);

// ---- cage centroid trajectory (seed 001 section 4) --------------------------------------------

struct CentroidMetrics {
  double centre_x = 0, centre_y = 0;  ///< m, mean centre of the cage over the window

  /// Vortex radius r_i = |(x_i, y_i) - mean centre|. Measured about the window's mean centre, not
  /// the bearing axis: under a radial load the inner ring and with it the cage's orbit shift by
  /// the ring's deflection and the clearance, and about the axis that offset would read as a large
  /// radius whose max - min mixes the whirl with where the orbit sits.
  double radius_mean = 0, radius_min = 0, radius_max = 0;  ///< m
  double radius_ratio = 0;  ///< vortex radius ratio (max - min) / mean of r_i; NaN if mean is 0

  /// The same about the bearing axis (x = y = 0): the eccentricity of the cage in the bearing.
  double axis_radius_mean = 0, axis_radius_min = 0, axis_radius_max = 0;  ///< m
  double axis_radius_ratio = 0;

  /// Centroid speed v_i = |(vx_i, vy_i)| (the in-plane centre velocity).
  double speed_mean = 0;  ///< m/s
  double speed_std = 0;   ///< m/s, sample standard deviation (n - 1)
  double sigma_v = 0;     ///< vortex velocity deviation ratio speed_std / speed_mean (seed 001 eq. 9)

  /// Whirl: mean rate of the centroid's angle about the mean centre (unwrapped), i.e. (phi_last -
  /// phi_first) / (t_last - t_first). Positive = counter-clockwise (+z). NaN (and radius_ratio
  /// NaN) if the centre does not move beyond the rounding error of its coordinates.
  double whirl_frequency = 0;     ///< rad/s
  double whirl_frequency_hz = 0;  ///< whirl_frequency / 2 pi
  double whirl_to_cage_ratio = 0; ///< whirl_frequency / mean cage speed; NaN if that speed is 0
  double revolutions = 0;         ///< unwrapped angle swept over the window / 2 pi
};

/// Vortex metrics of the cage centre (x, y) with centre velocity (vx, vy), all of the size of
/// time. The centroid speed comes from the velocity series (not from differences of positions).
/// cage_speed_mean (rad/s) scales the whirl ratio.
CentroidMetrics centroid_metrics(std::span<const double> time, std::span<const double> x,
                                 std::span<const double> y, std::span<const double> vx,
                                 std::span<const double> vy, const TimeWindow& window,
                                 double cage_speed_mean);

// ---- cage pocket (bar) forces (seed 000 figures 6-9) ------------------------------------------

/// Pocket contact force split onto the two bars of each pocket. front[k][i] and rear[k][i] are the
/// normal force (N, >= 0) of pocket k at sample i on its front and rear bar (0 when that bar is not
/// touched). Pocket k holds ball k.
struct BarForces {
  std::vector<std::vector<double>> front;
  std::vector<std::vector<double>> rear;
  int direction = 1;  ///< +1: cage turning in +z, -1: in -z (sign of the mean cage speed)
};

/// Direction of the cage (sign of its mean speed; +1 for 0 or NaN).
int cage_direction(double cage_speed_mean);

/// Splits the ball-pocket contacts onto bars. normal_force and circumferential_force are
/// row-major [T x s] (s columns, one per ball_pocket segment), ball[c] the ball (pocket) index of
/// column c in [0, pockets). circumferential_force is the force of the cage on the ball along
/// e_theta = e_z x e_r. With the cage turning in +z a negative value means the ball presses on
/// the bar ahead of it (front), a positive one that the bar behind it (rear) pushes it; with the
/// cage turning in -z the sides swap (docs/output_layout.md). So column c's normal force goes to
/// the front bar when circumferential_force * direction < 0, else to the rear bar; several
/// columns of one pocket add up.
BarForces split_bar_forces(std::span<const double> normal_force, std::span<const double> circumferential_force,
                           std::span<const int> ball, std::size_t pockets, int direction);

/// Contact statistics of one force series on one bar over the window.
struct ContactStats {
  double rms = 0;            ///< N, sqrt(time mean of F^2) over the window
  double peak = 0;           ///< N, max |F|
  double impulse = 0;        ///< N s, integral of |F| dt (trapezoid)
  std::size_t events = 0;    ///< separate contacts: runs of consecutive samples with F > threshold
  double contact_time = 0;   ///< s, sum of the trapezoid weights of the samples in contact
  double mean_duration = 0;  ///< s, contact_time / events; NaN without events
  double duty_cycle = 0;     ///< contact_time / window length
};

/// Statistics of force (size of time) over the window with the contact threshold (N). A contact
/// already going on at the window's start counts as an event.
ContactStats contact_stats(std::span<const double> time, std::span<const double> force, const TimeWindow& window,
                           double threshold);

/// Default contact threshold: 1 % of the peak force of all pockets and bars over the window, at
/// least 1e-3 N.
double default_contact_threshold(const BarForces& bars, const TimeWindow& window);

struct PocketForceSummary {
  double threshold = 0;                     ///< N, contact threshold used
  std::vector<ContactStats> front, rear;    ///< per pocket
  ContactStats front_total, rear_total;     ///< events, impulse, contact time summed over pockets;
                                            ///< rms over all pockets (root of the mean of the mean
                                            ///< squares); peak the max; duty cycle the mean;
                                            ///< mean_duration contact_time / events
  double rear_impulse_fraction = 0;         ///< rear impulse / (front + rear impulse); NaN if both 0
  double rms_circumferential_force = 0;     ///< N, RMS of the pocket circumferential force over
                                            ///< all pockets and the window (one column per pocket)
  double mean_net_circumferential_force = 0;///< N, time mean of the sum over pockets (the cage's
                                            ///< net drive; cage drag balance at steady state)
};

/// Per-pocket and total bar-force statistics. circumferential_force and ball as in
/// split_bar_forces (for the circumferential RMS). threshold: default_contact_threshold if not
/// given.
PocketForceSummary pocket_force_summary(std::span<const double> time, const BarForces& bars,
                                        std::span<const double> circumferential_force, std::span<const int> ball,
                                        const TimeWindow& window, std::optional<double> threshold = std::nullopt);

// ---- azimuth binning ---------------------------------------------------------------------------

/// atan2(y, x) mapped to [0, 2 pi).
double azimuth(double x, double y);

/// Values binned by azimuth: bins [k w, (k + 1) w) for k = 0 .. ceil(2 pi / w) - 1 (the last bin
/// ends at 2 pi and may be narrower).
struct AzimuthBins {
  double width = 0;                 ///< rad
  std::vector<double> lower;        ///< rad, lower edge of each bin
  std::vector<double> centre;       ///< rad, middle of each bin
  std::vector<double> mean;         ///< mean of the values in the bin (NaN if empty)
  std::vector<double> max;          ///< max of the values in the bin (NaN if empty)
  std::vector<std::size_t> count;   ///< samples in the bin
  double upper(std::size_t k) const;  ///< upper edge of bin k (rad)
};

/// Bins value[i] at azimuth[i] (rad, any range: wrapped to [0, 2 pi)). width in rad, in
/// (0, 2 pi]. Non-finite values or azimuths are skipped.
AzimuthBins bin_by_azimuth(std::span<const double> azimuth_rad, std::span<const double> value, double width);

/// The loaded zone of a binned load: the widest circular run of bins whose mean exceeds the
/// threshold. Empty bins (no samples: a short run does not take every ball through every azimuth)
/// inside a run do not break it; the run's end bins are loaded ones. start and end are its outer
/// edges (rad, end may be < start when the zone wraps through 0); width = end - start mod 2 pi;
/// centre the middle. No unloaded bin: start = 0, width = 2 pi. No loaded bin: all NaN.
struct LoadZone {
  double start = 0, end = 0, width = 0, centre = 0;  ///< rad
};
LoadZone load_zone(const AzimuthBins& bins, double threshold);

/// Per-ball inner-groove load: the normal forces [T x s] (row-major) of the columns of each ball
/// added (four-point bearings: both arcs of a ball). Returns [T x balls] row-major.
std::vector<double> ball_loads(std::span<const double> normal_force, std::span<const int> ball, std::size_t balls);

}  // namespace raceway::io
