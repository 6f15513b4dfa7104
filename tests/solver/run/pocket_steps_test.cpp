// The step-resolved pocket statistics (solver/run/pocket_steps.hpp) on synthetic records: the sides
// (spatial by the sign of the circumferential force, planar by the bar), onsets, peaks and the
// trapezoid impulse and contact time against hand-computed values, an evaluation past an output
// time going to the next row, a restart dropping it, and a checkpoint round trip continuing bitwise.
#include "solver/run/pocket_steps.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "solver/bearing/segment_record.hpp"

namespace raceway::run {
namespace {

constexpr int circumferential = contact::field_index(contact::point_diagnostic_fields, "circumferential_force");

/// Two balls, each with one pocket segment, and a groove segment the statistics must ignore.
bearing::Model two_ball_model() {
  bearing::Model m;
  m.kind = scene::ModelKind::spatial;
  m.element_count = 2;
  m.segments.push_back({bearing::SegmentKind::ball_inner_groove, 0, 3, 0, 0, "ball[0]/inner"});
  m.segments.push_back({bearing::SegmentKind::ball_pocket, 2, 3, 0, 0, "ball[0]/pocket"});
  m.segments.push_back({bearing::SegmentKind::ball_pocket, 2, 4, 0, 1, "ball[1]/pocket"});
  return m;
}

/// Records with pocket normal forces fn[k] (segment k + 1) and circumferential forces fc[k].
std::vector<double> records(const bearing::Model& m, std::vector<double> fn, std::vector<double> fc, double groove = 5.0) {
  std::vector<double> r(m.segments.size() * bearing::SegmentRecord::size, 0.0);
  r[bearing::SegmentRecord::diagnostics + bearing::normal_force_field] = groove;
  for (std::size_t k = 0; k < fn.size(); ++k) {
    double* d = r.data() + (k + 1) * bearing::SegmentRecord::size + bearing::SegmentRecord::diagnostics;
    d[bearing::normal_force_field] = fn[k];
    d[circumferential] = fc[k];
  }
  return r;
}

/// Row value: quantity q (onsets, peak, impulse, contact time), pocket k, side s.
double at(const std::vector<double>& row, int q, int k, int s) {
  return row[static_cast<std::size_t>((q * 2 + k) * PocketSteps::sides + s)];
}

TEST(PocketSteps, SidesOnsetsPeaksAndTrapezoids) {
  const bearing::Model m = two_ball_model();
  PocketSteps p(m);
  ASSERT_TRUE(p.active());
  ASSERT_EQ(p.pockets(), 2);
  std::vector<double> row;
  // Ball 0: on side 0 (fc < 0) from t = 2; ball 1: side 1 (fc > 0) at t = 3 only.
  p.observe(1.0, records(m, {0.0, 0.0}, {0.0, 0.0}));
  p.observe(2.0, records(m, {4.0, 0.0}, {-1.0, 0.0}));
  p.observe(3.0, records(m, {6.0, 2.0}, {-1.0, 0.5}));
  p.take_row(3.0, row);
  EXPECT_EQ(at(row, 0, 0, 0), 1.0);  // one onset (t = 1 -> 2); the first evaluation only starts
  EXPECT_EQ(at(row, 0, 0, 1), 0.0);
  EXPECT_EQ(at(row, 0, 1, 1), 1.0);
  EXPECT_EQ(at(row, 1, 0, 0), 6.0);
  EXPECT_EQ(at(row, 1, 1, 1), 2.0);
  EXPECT_EQ(at(row, 2, 0, 0), 0.5 * (0 + 4) * 1 + 0.5 * (4 + 6) * 1);
  EXPECT_EQ(at(row, 3, 0, 0), 0.5 + 1.0);
  EXPECT_EQ(at(row, 2, 1, 1), 1.0);
  EXPECT_EQ(at(row, 3, 1, 1), 0.5);
  // A contact going on at the next interval's start is not an onset there.
  p.observe(4.0, records(m, {8.0, 0.0}, {-1.0, 0.0}));
  p.take_row(4.0, row);
  EXPECT_EQ(at(row, 0, 0, 0), 0.0);
  EXPECT_EQ(at(row, 1, 0, 0), 8.0);
  EXPECT_EQ(at(row, 2, 0, 0), 7.0);
}

TEST(PocketSteps, PlanarBarsBySegmentKind) {
  bearing::Model m;
  m.element_count = 1;
  m.segments.push_back({bearing::SegmentKind::cage_bar_front, 2, 3, 0, 0, "roller[0]/cage_bar_front"});
  m.segments.push_back({bearing::SegmentKind::cage_bar_rear, 2, 3, 0, 0, "roller[0]/cage_bar_rear"});
  PocketSteps p(m);
  std::vector<double> r(2 * bearing::SegmentRecord::size, 0.0), row;
  p.observe(0.0, r);
  r[bearing::SegmentRecord::size + bearing::SegmentRecord::diagnostics + bearing::normal_force_field] = 3.0;  // the rear bar
  p.observe(1.0, r);
  p.take_row(1.0, row);
  ASSERT_EQ(row.size(), 4U * 2U);
  EXPECT_EQ(row[1 * 2 + 1], 3.0);  // peak, pocket 0, side 1
  EXPECT_EQ(row[1 * 2 + 0], 0.0);
}

TEST(PocketSteps, AnEvaluationPastTheOutputTimeGoesToTheNextRowOrIsDroppedAtARestart) {
  const bearing::Model m = two_ball_model();
  std::vector<double> row;
  for (const bool restart : {false, true}) {
    PocketSteps p(m);
    p.observe(1.0, records(m, {0.0, 0.0}, {0.0, 0.0}));
    p.observe(2.5, records(m, {5.0, 0.0}, {-1.0, 0.0}));  // the step that passed the output time 2
    p.take_row(2.0, row);
    EXPECT_EQ(at(row, 1, 0, 0), 0.0);
    if (restart) p.restart();  // integrated again from t = 2
    p.observe(3.0, records(m, {1.0, 0.0}, {-1.0, 0.0}));
    p.take_row(3.0, row);
    EXPECT_EQ(at(row, 0, 0, 0), 1.0);
    EXPECT_EQ(at(row, 1, 0, 0), restart ? 1.0 : 5.0);
    EXPECT_EQ(at(row, 2, 0, 0), restart ? 0.5 * 1.0 * 2.0 : 0.5 * 5.0 * 1.5 + 0.5 * 6.0 * 0.5);
  }
}

TEST(PocketSteps, ACheckpointRoundTripContinuesBitwise) {
  const bearing::Model m = two_ball_model();
  PocketSteps a(m), b(m);
  std::vector<double> row_a, row_b;
  a.observe(0.1, records(m, {0.0, 0.3}, {0.0, 1.0}));
  a.observe(0.37, records(m, {1.7, 0.1}, {-2.0, 1.0}));
  a.take_row(0.4, row_a);
  Checkpoint cp;
  a.save(cp);
  b.restore(cp);
  for (PocketSteps* p : {&a, &b}) {
    p->restart();
    p->observe(0.53, records(m, {0.9, 0.0}, {-2.0, 0.0}));
    p->observe(0.61, records(m, {0.0, 0.2}, {0.0, 3.0}));
  }
  a.take_row(0.8, row_a);
  b.take_row(0.8, row_b);
  EXPECT_EQ(row_a, row_b);
  EXPECT_EQ(a.totals_json().dump(), b.totals_json().dump());
}

}  // namespace
}  // namespace raceway::run
