// A dry ball pocket whose ball stands clear of it by more than its Jacobian columns' steps can close
// writes zero columns without evaluating its law (pocket_stays_clear,
// solver/bearing/element_evaluation.hpp). On 6309 R3, seated and with the cage turned until ball 0
// presses into its pocket: every pocket's Jacobian record is bit for bit the one forward differences
// of the law at every column give, every pocket judged clear has exactly zero wrenches at every
// column's step, and both kinds occur.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "solver/bearing/element_evaluation.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

TEST(PocketJacobian, ClearPocketsHaveExactlyZeroColumns) {
  const Model m = build_model(test::load_job_scene("6309_R3.toml"));
  const FiniteDifferenceSteps step(m);
  const std::vector<double> seated = initial_state(m, 0.0).state;
  int cage = -1;
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (m.bodies[b].kind == BodyKind::cage) cage = static_cast<int>(b);
  ASSERT_GE(cage, 0);
  // 0.4 mm diametral clearance at 36 mm: a pocket's bar is about 5.5 mrad away.
  std::vector<double> turned = seated;
  turned[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(cage)].slot[saz])] += 7e-3;
  const double t = 1e-3;
  int clear = 0, evaluated = 0;
  for (const std::vector<double>& z : {seated, turned}) {
    for (const Segment& seg : m.segments) {
      if (seg.kind != SegmentKind::ball_pocket) continue;
      const auto& law = m.law<contact::BallPocketSegment>(seg);
      const ElementShape shape = element_shape(m, seg);
      const auto at = [&](const std::vector<double>& y) {
        return contact::evaluate(law, m.kinematics(seg.body_a, t, y.data()), m.kinematics(seg.body_b, t, y.data()));
      };
      const contact::SpatialSegmentResult base = at(z);
      const bool judged_clear =
          element_detail::pocket_stays_clear(m, step, law, seg, shape, z.data(), m.kinematics(seg.body_a, t, z.data()),
                                             m.kinematics(seg.body_b, t, z.data()), base);
      (judged_clear ? clear : evaluated) += 1;
      // The record by forward differences of the law at every column, against the one written.
      std::vector<double> expected(static_cast<std::size_t>(SegmentRecord::size + SegmentRecord::wrench_rows * shape.record_columns()));
      std::vector<double> written(expected.size());
      double* out = expected.data() + SegmentRecord::size;
      for (const SegmentColumn& c : shape.columns) {
        std::vector<double> y = z;
        const double h = step(c.state, z.data());
        y[static_cast<std::size_t>(c.state)] += h;
        const contact::SpatialSegmentResult r = at(y);
        if (judged_clear)
          for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(r.on_a.force[i], 0.0) << seg.name;
            EXPECT_EQ(r.on_a.moment[i], 0.0) << seg.name;
            EXPECT_EQ(r.on_b.force[i], 0.0) << seg.name;
            EXPECT_EQ(r.on_b.moment[i], 0.0) << seg.name;
          }
        write_difference(r, base, 1.0 / h, out);
        out += SegmentRecord::wrench_rows;
      }
      write_result(base, expected);
      expected[SegmentRecord::valid] = base.valid ? 1.0 : 0.0;
      write_element_jacobian(m, step, law, seg, shape, t, z.data(), written);
      EXPECT_EQ(std::memcmp(expected.data(), written.data(), expected.size() * sizeof(double)), 0) << seg.name;
    }
  }
  std::printf("[ jacobian ] ball pockets judged clear %d, evaluated %d\n", clear, evaluated);
  EXPECT_GT(clear, 0);
  EXPECT_GT(evaluated, 0);
}

}  // namespace
}  // namespace raceway::bearing
