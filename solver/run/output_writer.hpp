// The output file's model-dependent layout (docs/output_layout.md), written from one table: per
// body group the series it stores (name, which components of the body's sampled quantities, unit,
// meaning), per segment kind the diagnostics of its family's field table. A planar bearing stores
// the planar components (x, y, rotation about z) of the same quantities a spatial one stores in full.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/h5/h5_series.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/run/power_balance.hpp"
#include "solver/run/thermal_series.hpp"

namespace raceway::run {

/// What the output knows of one body at one sample.
struct BodySample {
  contact::Vec3 position, velocity;          ///< m, m/s: centre, bearing frame
  contact::Vec3 angles;                      ///< rad: tilts / Cardan angles about x, y; rotation about z
  contact::Vec3 angular_velocity;            ///< rad/s, bearing frame
  double acceleration[6] = {0, 0, 0, 0, 0, 0};  ///< m/s^2 x y z, rad/s^2 about x y z (0 where not a state)
  double force[6] = {0, 0, 0, 0, 0, 0};         ///< N x y z, N m about x y z: net, at the centre
};

/// The size of a run's output file (docs/output_layout.md), from the same tables the writer uses:
/// `raceway check` prints it, and run_scene holds it against [output] max_size before it creates
/// the file. The series uncompressed (what they cannot exceed) and an upper bound of the rest:
/// names, attributes, HDF5's object headers and chunk indexes, the summary and the fixed part of
/// the /scheduler log; the /scheduler log's arrays get what max_size leaves over (they are thinned
/// to fit: write_schedule_log).
struct OutputEstimate {
  long samples = 0;            ///< output times, t = 0 included
  long values_per_sample = 0;  ///< doubles appended per output time (segment diagnostics included)
  long segment_values = 0;     ///< of them the segment diagnostics, at every segment_every-th sample only
  int segment_every = 1;       ///< [output] segment_every
  double bytes = 0;            ///< the series: samples x values x 8
  double fixed_bytes = 0;      ///< everything else but the /scheduler log's arrays
  double total() const { return bytes + fixed_bytes; }
  /// "output: 201 samples x 1234 values = 1.99 MB + 120 kB of names, attributes and indexes
  /// (limit 4 GB, [output] max_size)".
  std::string describe(double limit) const;
};
OutputEstimate estimate_output(const bearing::Model& m, const scene::Scene& scene);
/// Throws scene::SceneError (bad input) naming output_interval, end_time and max_size, with the
/// numbers, when the estimate exceeds [output] max_size.
void check_output_size(const OutputEstimate& estimate, const scene::Scene& scene);

/// The root attributes that describe the bearing, written for every run (docs/output_layout.md,
/// "Bearing attributes"): its kind, the rolling elements, the geometry in SI (radii, clearances,
/// contact angle) and the integrator's tolerances of the element positions, so that readers never
/// parse the model's description.
void write_bearing_attributes(h5::H5SeriesWriter& file, const bearing::Model& m, const scene::Scene& scene);

BodySample sample_body(const bearing::Model& m, int b, double t, const std::vector<double>& z, const std::vector<double>& zdot,
                       const bearing::Wrench& net);

/// The segment diagnostic series of the layout (the series the parallel output shares between
/// ranks), by path: the diagnostic's position in its family's field table, the segment of each
/// column and the output samples of its rows (row r: sample r x stride, [output] segment_every).
struct SegmentSeries {
  int field = 0;
  std::vector<int> segments;
  long stride = 1;
};
std::map<std::string, SegmentSeries> segment_series(const bearing::Model& m);

class OutputWriter {
 public:
  /// Defines the layout for the model (segment diagnostics only if `segments`, at every
  /// `segment_every`-th sample; written by all ranks together if `shared_segments`: the file has a
  /// shared writer, see H5SeriesWriter).
  OutputWriter(h5::H5SeriesWriter& file, const bearing::Model& m, bool segments, bool shared_segments = false,
               int segment_every = 1);
  /// Whether output sample `sample` (0 at t = 0, counted from the run's start) stores the segment
  /// diagnostics: [output] segments, at every segment_every-th sample.
  bool stores_segments(long sample) const { return segments_ && sample % segment_every_ == 0; }
  /// Appends output time t: rhs at (t, z) has just filled zdot and the equations' records.
  /// `pocket_steps`: the step-resolved pocket statistics of the interval ending at t
  /// (solver/run/pocket_steps.hpp: quantities x pockets x sides; empty for a model without pockets),
  /// then the housing sensor's samples of that interval (solver/run/housing_sensor.hpp), then the
  /// power balance's work up to t (solver/run/power_balance.hpp).
  /// `sample`: the output sample's index from the run's start (stores_segments).
  /// `segment_rank`: with shared segments, the rank that evaluated each segment in that rhs (this
  /// process writes the diagnostics of rank 0's).
  void append(double t, const std::vector<double>& z, const std::vector<double>& zdot, const bearing::Equations& eq,
              double energy, const std::vector<double>& pocket_steps, long sample,
              const std::vector<int>* segment_rank = nullptr);

  /// Load-weighted mean |contact angle| of the inner-groove contacts in the last rhs (the angle the
  /// balls roll at); the nominal angle when none is loaded.
  static double loaded_contact_angle(const bearing::Model& m, const bearing::Equations& eq);
  /// The kinematic cage speed at that angle at time t (/cage/rolling_speed): the cage speed of
  /// elements rolling without slip at the angle they are loaded at. Planar: the epicyclic speed of
  /// line contacts (0 deg).
  static double rolling_cage_speed(const bearing::Model& m, const bearing::Equations& eq, double t);

 private:
  void define_segment_groups();
  void define_pocket_steps();
  void define_housing_sensor();
  void append_bodies(double t, const std::vector<double>& z, const std::vector<double>& zdot, const bearing::Equations& eq);

  h5::H5SeriesWriter& file_;
  const bearing::Model& m_;
  bool segments_, shared_;
  int segment_every_ = 1;  ///< [output] segment_every
  std::vector<unsigned char> mine_;  ///< reused: which cells of a shared row this process writes
  // The series' handles in the order append() writes them (looked up once, not per sample).
  h5::H5SeriesWriter::SeriesId time_ = 0, energy_ = 0, epicyclic_ = 0, rolling_ = 0, segment_time_ = 0;
  std::vector<h5::H5SeriesWriter::SeriesId> border_ids_, element_ids_, pocket_step_ids_, sensor_ids_;
  PowerBalanceSeries power_;
  std::optional<ThermalSeries> thermal_;
  std::size_t sensor_per_ = 0;    ///< the housing sensor's samples per row
  std::size_t pocket_cells_ = 0;  ///< doubles of the pocket statistics in a step row (the sensor's follow)
  std::vector<h5::H5SeriesWriter::SeriesId> diagnostic_ids_[bearing::segment_kind_count];
  std::vector<double> row_;  ///< reused row buffer
  std::vector<BodySample> samples_;  ///< the rolling elements' samples, reused
  std::vector<int> index_[bearing::segment_kind_count];  ///< segments of each kind, in column order
  bool line_family_[bearing::segment_kind_count] = {};    ///< the kind's diagnostics: line (else point) field table
};

}  // namespace raceway::run
