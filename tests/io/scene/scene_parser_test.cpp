// Scene parser: the default scene, defaults and conversions to SI, planar and spatial rules.
// The job scenes and tests/io/scene/bad_scenes are in scene_files_test.cpp, the contact laws in
// scene_laws_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "tests/support/scene_test_util.hpp"

namespace raceway::scene {
namespace {

using namespace test;

TEST(DefaultScene, Parses) {
  const Scene s = default_scene();
  EXPECT_EQ(s.source, "<built-in default>");
  EXPECT_EQ(s.text, default_scene_text());
  EXPECT_EQ(s.scene.name, "default");
  EXPECT_EQ(s.scene.model, ModelKind::planar);
  EXPECT_DOUBLE_EQ(s.scene.end_time, 0.1);
  EXPECT_DOUBLE_EQ(s.scene.output_interval, 5e-4);
  EXPECT_FALSE(s.gravity);

  const BearingGeometry& b = s.bearing;
  EXPECT_EQ(b.type, BearingType::cylindrical_roller);
  EXPECT_EQ(b.rolling_elements, 8);
  EXPECT_DOUBLE_EQ(b.roller_diameter, 6e-3);
  EXPECT_DOUBLE_EQ(b.roller_length, 6e-3);
  EXPECT_DOUBLE_EQ(b.pitch_diameter, 30e-3);
  EXPECT_DOUBLE_EQ(b.radial_clearance, 0.0);
  EXPECT_NEAR(b.inner_bore_diameter, 18e-3, 1e-15);     // default: inner race - D
  EXPECT_NEAR(b.outer_outside_diameter, 42e-3, 1e-15);  // default: outer race + D
  EXPECT_DOUBLE_EQ(b.ring_width, 6e-3);
  EXPECT_EQ(b.roller_material, "steel");
  EXPECT_EQ(b.ring_material, "steel");
  EXPECT_DOUBLE_EQ(s.material("steel").youngs_modulus, 208e9);
  EXPECT_DOUBLE_EQ(s.material("brass").density, 8500.0);
  EXPECT_DOUBLE_EQ(s.material("polyamide").poisson_ratio, 0.4);

  EXPECT_EQ(s.cage.guidance, CageGuidance::inner_land);
  EXPECT_DOUBLE_EQ(s.cage.pocket_clearance, 0.2e-3);
  EXPECT_DOUBLE_EQ(s.cage.land_clearance, 0.3e-3);
  EXPECT_DOUBLE_EQ(s.cage.bar_width, 6e-3);
  EXPECT_DOUBLE_EQ(s.cage.land_width, 3e-3);
  EXPECT_EQ(s.cage.material, "brass");
  EXPECT_EQ(s.cage.mass, 0.0);

  EXPECT_EQ(s.inner_ring.motion, RingMotion::driven);
  EXPECT_NEAR(s.inner_ring.speed(0.0), 1500.0 * pi / 30.0, 1e-12);
  EXPECT_TRUE(s.inner_ring.translation_free);
  EXPECT_TRUE(s.inner_ring.load.fx.is_zero());
  EXPECT_DOUBLE_EQ(s.inner_ring.load.fy(0.05), -500.0);
  EXPECT_TRUE(s.inner_ring.load.mz.is_zero());
  EXPECT_EQ(s.inner_ring.support.stiffness, 0.0);
  EXPECT_EQ(s.outer_ring.motion, RingMotion::fixed);
  EXPECT_FALSE(s.outer_ring.translation_free);

  EXPECT_EQ(s.roller_race.normal.name(), "palmgren");
  EXPECT_EQ(s.roller_race.normal.id, contact::LawId::palmgren);
  EXPECT_EQ(s.roller_race.normal.slices, 1);
  EXPECT_EQ(s.roller_race.damping.name(), "hunt_crossley");
  EXPECT_EQ(s.roller_race.damping.id, contact::LawId::hunt_crossley);
  EXPECT_DOUBLE_EQ(s.roller_race.damping.factor, 0.5);
  EXPECT_EQ(s.roller_race.traction.name(), "tanh");
  EXPECT_EQ(s.roller_race.traction.id, contact::LawId::tanh_traction);
  EXPECT_DOUBLE_EQ(s.roller_race.traction.friction_coefficient, 0.1);
  EXPECT_DOUBLE_EQ(s.roller_race.traction.slip_velocity_scale, 0.05);
  EXPECT_DOUBLE_EQ(s.cage_land.traction.friction_coefficient, 0.05);

  EXPECT_EQ(s.solver.method, IntegrationMethod::bdf);
  EXPECT_EQ(s.solver.max_order, 5);
  EXPECT_DOUBLE_EQ(s.solver.rtol, 1e-6);
  EXPECT_EQ(s.solver.atol_position, 0.0);
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::automatic);
  EXPECT_TRUE(s.output.segments);
}

TEST(DefaultScene, JobFileEqualsBuiltInText) {
  const fs::path job = kSourceDir / "jobs" / "scenes" / "default.toml";
  EXPECT_EQ(read_file(job), default_scene_text());
  const Scene s = load_scene(job.string());
  EXPECT_EQ(s.source, job.string());
  EXPECT_EQ(s.text, default_scene_text());
  EXPECT_EQ(s.bearing.rolling_elements, 8);
}

TEST(SceneParser, MinimalSceneGetsDocumentedDefaults) {
  const Scene s = parse(kPlanarMinimal);
  EXPECT_NEAR(s.bearing.inner_race_diameter(), 0.04 - 0.005 - 10e-6, 1e-15);
  EXPECT_NEAR(s.bearing.inner_bore_diameter, 0.04 - 0.005 - 10e-6 - 0.005, 1e-15);
  EXPECT_NEAR(s.bearing.outer_outside_diameter, 0.04 + 0.005 + 10e-6 + 0.005, 1e-15);
  EXPECT_DOUBLE_EQ(s.bearing.ring_width, 0.008);
  EXPECT_EQ(s.cage.guidance, CageGuidance::rolling_element);
  EXPECT_EQ(s.cage.land_clearance, 0.0);
  EXPECT_DOUBLE_EQ(s.cage.land_width, 0.004);
  EXPECT_EQ(s.cage.material, "brass");
  EXPECT_EQ(s.inner_ring.motion, RingMotion::free);
  EXPECT_TRUE(s.inner_ring.translation_free);
  EXPECT_DOUBLE_EQ(s.inner_ring.load.mz(1.0), 0.5);
  EXPECT_DOUBLE_EQ(s.inner_ring.support.stiffness, 1e8);
  EXPECT_DOUBLE_EQ(s.inner_ring.support.damping, 0.0);
  EXPECT_EQ(s.outer_ring.motion, RingMotion::driven);
  EXPECT_FALSE(s.outer_ring.translation_free);
  EXPECT_NEAR(s.outer_ring.speed(0.005), 10.0 * pi, 1e-12);
  EXPECT_NEAR(s.outer_ring.speed(1.0), 20.0 * pi, 1e-12);
  EXPECT_NEAR(s.outer_ring.speed.derivative(0.005), 20.0 * pi / 0.01, 1e-9);
  EXPECT_EQ(s.lubricant.viscosity, 0.0);
  EXPECT_EQ(s.roller_cage.normal.name(), "palmgren");
  EXPECT_DOUBLE_EQ(s.roller_cage.traction.friction_coefficient, 0.1);
  EXPECT_EQ(s.solver.max_steps, 500000000);
  EXPECT_DOUBLE_EQ(s.solver.jacobian_perturbation, 1e-7);
}

TEST(SceneParser, OptionalSectionsAndUserMaterials) {
  std::string text = edited("\n[output]\n", R"(
[lubricant]
name = "ISO VG 32"
viscosity = "30 mPa s"
pressure_viscosity = "20 1/GPa"

[materials.steel]
density = "7.8 g/cm^3"
youngs_modulus = "200 GPa"
poisson_ratio = 0.29

[materials.bronze]
density = "8800 kg/m^3"
youngs_modulus = "110 GPa"
poisson_ratio = 0.34

[output]
)");
  auto replace = [&](std::string_view from, std::string_view to) {
    const auto pos = text.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    text.replace(pos, from.size(), to);
  };
  replace("material = \"brass\"", "material = \"bronze\"");
  replace("method = \"bdf\"", "method = \"adams\"\natol = { position = \"1 nm\", angular_velocity = \"0.01 rpm\" }");
  replace("traction = \"tanh\"\nfriction_coefficient = 0.05\nslip_velocity_scale = \"0.05 m/s\"", "traction = \"none\"");
  replace("damping = \"hunt_crossley\"\ndamping_factor = \"0.5 s/m\"\ntraction = \"none\"",
          "damping = \"none\"\ntraction = \"none\"");
  const Scene s = parse(text);
  EXPECT_EQ(s.lubricant.name, "ISO VG 32");
  EXPECT_NEAR(s.lubricant.viscosity, 0.03, 1e-15);
  EXPECT_NEAR(s.lubricant.pressure_viscosity, 2e-8, 1e-20);
  EXPECT_NEAR(s.material("steel").density, 7800.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.material("steel").youngs_modulus, 200e9);
  EXPECT_EQ(s.material("bronze").name, "bronze");
  EXPECT_EQ(s.cage.material, "bronze");
  EXPECT_EQ(s.solver.method, IntegrationMethod::adams);
  EXPECT_EQ(s.solver.max_order, 12);
  EXPECT_DOUBLE_EQ(s.solver.atol_position, 1e-9);
  EXPECT_NEAR(s.solver.atol_angular_velocity, 0.01 * pi / 30.0, 1e-15);
  EXPECT_EQ(s.solver.atol_angle, 0.0);
  EXPECT_EQ(s.cage_land.traction.name(), "none");
  EXPECT_EQ(s.cage_land.traction.id, contact::LawId::no_traction);
  EXPECT_EQ(s.cage_land.traction.friction_coefficient, 0.0);
  EXPECT_DOUBLE_EQ(s.cage_land.traction.slip_velocity_scale, 0.05);  // kept at its default, unused
  EXPECT_EQ(s.cage_land.damping.name(), "none");
  EXPECT_EQ(s.cage_land.damping.id, contact::LawId::no_damping);
  EXPECT_EQ(s.cage_land.damping.factor, 0.0);
  EXPECT_EQ(s.roller_race.traction.name(), "tanh");
}

TEST(SceneParser, ErrorFormat) {
  const SceneError e = error_of(edited("roller_diameter = \"6 mm\"", "roller_diameter = \"6 rpm\""));
  EXPECT_EQ(e.file(), "edited.toml");
  EXPECT_EQ(e.key(), "bearing.roller_diameter");
  EXPECT_EQ(e.reason(), "'6 rpm' is an angular speed; expected a length (m, mm, um)");
  EXPECT_EQ(std::string(e.what()),
            "edited.toml:" + std::to_string(e.line()) + ": key 'bearing.roller_diameter': " + e.reason());
  // the line is that of the value
  const std::string text = default_scene_text();
  const auto pos = text.find("roller_diameter = ");
  EXPECT_EQ(e.line(), 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n')));
}

TEST(SceneParser, MoreRules) {
  // parameters of a law that is switched off are rejected, not ignored
  EXPECT_EQ(error_of(edited("damping = \"hunt_crossley\"", "damping = \"none\"")).key(),
            "contact.roller_race.damping_factor");
  // translation is meaningless for a fixed ring
  EXPECT_EQ(error_of(edited("motion = \"fixed\"", "motion = \"fixed\"\ntranslation = \"free\"")).key(),
            "outer_ring.translation");
  // a driven ring needs a speed
  EXPECT_EQ(error_of(edited("speed = \"1500 rpm\"", "")).key(), "inner_ring.speed");
  // a supported floating outer ring holds the bearing
  const Scene s = parse(edited("motion = \"fixed\"", "motion = \"free\"\nsupport = { stiffness = \"2e8 N/m\", damping = \"1e3 N s/m\" }"));
  EXPECT_DOUBLE_EQ(s.outer_ring.support.damping, 1e3);
  EXPECT_EQ(error_of(edited("rtol = 1e-6", "rtol = 0.1")).key(), "solver.rtol");
  EXPECT_EQ(error_of(edited("slices = 1", "slices = 0")).key(), "contact.roller_race.slices");
  EXPECT_EQ(error_of(edited("friction_coefficient = 0.1", "friction_coefficient = 1.5")).key(),
            "contact.roller_race.friction_coefficient");
  EXPECT_EQ(error_of(edited("gravity = false", "gravity = \"no\"")).key(), "scene.gravity");
  EXPECT_EQ(error_of(edited("\n[output]\n", "\n[output]\nframes = 3\n")).reason(),
            "unknown key 'frames' in [output]; allowed keys: segments, segment_every, max_size, checkpoint_interval, checkpoint_wall_interval");
}

TEST(SceneParser, UnreadableFile) {
  const std::string path = (kSourceDir / "tests/io/scene/bad_scenes" / "no_such_file.toml").string();
  try {
    (void)load_scene(path);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.key(), "");
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    EXPECT_NE(e.reason().find("cannot read the scene file"), std::string::npos);
  }
}

// ---- spatial (ball bearing) scenes ------------------------------------------------------------

TEST(SpatialScene, MinimalSceneGetsDocumentedDefaults) {
  const Scene s = parse(spatial());
  EXPECT_EQ(s.scene.model, ModelKind::spatial);
  const BearingGeometry& b = s.bearing;
  EXPECT_EQ(b.type, BearingType::deep_groove_ball);
  EXPECT_TRUE(b.is_ball_bearing());
  EXPECT_DOUBLE_EQ(b.ball.ball_diameter, 17.462e-3);
  EXPECT_DOUBLE_EQ(b.element_diameter(), 17.462e-3);
  EXPECT_EQ(b.roller_diameter, 0.0);
  EXPECT_EQ(b.roller_length, 0.0);
  EXPECT_DOUBLE_EQ(b.ball.inner_conformity, 0.52);
  EXPECT_DOUBLE_EQ(b.ball.outer_conformity, 0.53);
  EXPECT_EQ(b.ball.arc_contact_angle, 0.0);
  EXPECT_NEAR(b.radial_clearance, 15e-6, 1e-18);
  EXPECT_NEAR(b.inner_race_diameter(), (72.5 - 17.462 - 0.0075) * 1e-3, 1e-15);
  EXPECT_NEAR(b.inner_bore_diameter, b.inner_race_diameter() - 17.462e-3, 1e-15);     // default
  EXPECT_NEAR(b.outer_outside_diameter, b.outer_race_diameter() + 17.462e-3, 1e-15);  // default
  EXPECT_EQ(b.roller_material, "steel");

  const CageSpec& c = s.cage;
  EXPECT_EQ(c.guidance, CageGuidance::rolling_element);
  EXPECT_EQ(c.pocket_shape, PocketShape::spherical);  // given: a ball-guided cage needs pockets that hold it
  EXPECT_DOUBLE_EQ(c.pocket_clearance, 0.4e-3);
  EXPECT_EQ(c.bar_width, 0.0);
  EXPECT_NEAR(c.land_width, 25e-3 - 17.462e-3, 1e-15);  // the two shoulders beside the groove
  EXPECT_NEAR(c.inner_diameter, 72.5e-3 - 0.6 * 17.462e-3, 1e-15);
  EXPECT_NEAR(c.outer_diameter, 72.5e-3 + 0.6 * 17.462e-3, 1e-15);
  EXPECT_NEAR(c.width, 0.8 * 25e-3, 1e-15);
  EXPECT_FALSE(c.support.any());
  EXPECT_EQ(c.transverse_inertia, 0.0);

  EXPECT_EQ(s.inner_ring.motion, RingMotion::driven);
  EXPECT_TRUE(s.inner_ring.translation_free);
  EXPECT_TRUE(s.inner_ring.axial_free);
  EXPECT_EQ(s.inner_ring.tilt, RingTilt::fixed);
  EXPECT_TRUE(s.inner_ring.load.fz.is_zero());
  EXPECT_TRUE(s.inner_ring.misalignment_x.is_zero());
  EXPECT_EQ(s.outer_ring.motion, RingMotion::fixed);
  EXPECT_FALSE(s.outer_ring.translation_free);
  EXPECT_FALSE(s.outer_ring.axial_free);
  EXPECT_EQ(s.outer_ring.tilt, RingTilt::fixed);

  // Point contacts: Hertz, Hunt-Crossley 0.5 s/m, tanh mu = 0.1 at 0.05 m/s, a 5 x 5 grid; no
  // lubricant, so no rolling resistance.
  EXPECT_EQ(s.ball_race.normal.name(), "hertz");
  EXPECT_EQ(s.ball_race.normal.id, contact::LawId::hertz);
  EXPECT_EQ(s.ball_race.damping.name(), "hunt_crossley");
  EXPECT_DOUBLE_EQ(s.ball_race.damping.factor, 0.5);
  EXPECT_EQ(s.ball_race.traction.name(), "tanh");
  EXPECT_DOUBLE_EQ(s.ball_race.traction.friction_coefficient, 0.1);
  EXPECT_DOUBLE_EQ(s.ball_race.traction.slip_velocity_scale, 0.05);
  EXPECT_EQ(s.ball_race.traction.grid_x, 5);
  EXPECT_EQ(s.ball_race.traction.grid_y, 5);
  EXPECT_FALSE(s.ball_race.traction.rolling_resistance);
  EXPECT_EQ(s.ball_cage.normal.name(), "hertz");
  EXPECT_EQ(s.ball_cage.traction.name(), "tanh");
  EXPECT_DOUBLE_EQ(s.ball_cage.traction.friction_coefficient, 0.1);
  EXPECT_EQ(s.cage_land.normal.name(), "palmgren");
  EXPECT_EQ(s.cage_land.normal.id, contact::LawId::palmgren);
  EXPECT_DOUBLE_EQ(s.cage_land.traction.friction_coefficient, 0.05);

  // With a lubricant, rolling resistance is on by default.
  const Scene lubricated = parse(spatial("", "[lubricant]\nviscosity = \"30 mPa s\"\n"));
  EXPECT_TRUE(lubricated.ball_race.traction.rolling_resistance);
  EXPECT_EQ(lubricated.lubricant.limiting_shear_coefficient, 0.0);
}

TEST(SpatialScene, RingsCageAndContactsInSI) {
  std::string text = spatial(R"([outer_ring]
motion = "fixed"
)",
                             R"([outer_ring]
motion = "free"
tilt = "free"
load = { fz = "-0.5 kN", mx = "2 N m", my = { time = ["0 s", "10 ms"], value = ["0 N m", "4 N m"] } }
support = { stiffness = "2e8 N/m", damping = "1e3 N s/m", axial_stiffness = "1e8 N/mm", tilt_stiffness = "5e4 N m/rad", tilt_damping = "2 N m s/rad" }
transverse_inertia = "4e-3 kg m^2"
[lubricant]
viscosity = "0.03 Pa s"
pressure_viscosity = "20 1/GPa"
limiting_shear_coefficient = 0.07
[contact.ball_race]
traction = "limiting_shear"
grid = [7, 3]
rolling_resistance = false
[contact.ball_cage]
damping = "none"
traction = "none"
)");
  const auto pos = text.find("pocket_clearance = \"0.4 mm\"");
  ASSERT_NE(pos, std::string::npos);
  text.insert(pos, "support = { axial_stiffness = \"1e7 N/m\" }\n");  // pocket_shape: spherical, as given
  const Scene s = parse(text);
  const RingSpec& o = s.outer_ring;
  EXPECT_EQ(o.motion, RingMotion::free);
  EXPECT_TRUE(o.axial_free);
  EXPECT_EQ(o.tilt, RingTilt::free);
  EXPECT_DOUBLE_EQ(o.load.fz(0.0), -500.0);
  EXPECT_DOUBLE_EQ(o.load.mx(0.0), 2.0);
  EXPECT_DOUBLE_EQ(o.load.my(0.005), 2.0);
  EXPECT_DOUBLE_EQ(o.support.stiffness, 2e8);
  EXPECT_DOUBLE_EQ(o.support.axial_stiffness, 1e11);
  EXPECT_EQ(o.support.axial_damping, 0.0);
  EXPECT_DOUBLE_EQ(o.support.tilt_stiffness, 5e4);
  EXPECT_DOUBLE_EQ(o.support.tilt_damping, 2.0);
  EXPECT_DOUBLE_EQ(o.transverse_inertia, 4e-3);
  EXPECT_EQ(s.cage.pocket_shape, PocketShape::spherical);
  EXPECT_DOUBLE_EQ(s.cage.support.axial_stiffness, 1e7);
  EXPECT_TRUE(s.cage.support.any());
  EXPECT_NEAR(s.lubricant.pressure_viscosity, 2e-8, 1e-22);
  EXPECT_DOUBLE_EQ(s.lubricant.limiting_shear_coefficient, 0.07);
  EXPECT_EQ(s.ball_race.traction.name(), "limiting_shear");
  EXPECT_EQ(s.ball_race.traction.id, contact::LawId::limiting_shear);
  EXPECT_EQ(s.ball_race.traction.grid_x, 7);
  EXPECT_EQ(s.ball_race.traction.grid_y, 3);
  EXPECT_FALSE(s.ball_race.traction.rolling_resistance);
  EXPECT_EQ(s.ball_cage.damping.name(), "none");
  EXPECT_EQ(s.ball_cage.traction.name(), "none");
  EXPECT_EQ(s.ball_cage.traction.friction_coefficient, 0.0);

  // A prescribed misalignment as a function of time, on a fixed ring (a misaligned housing).
  const Scene m = parse(spatial("motion = \"fixed\"\n",
                                "motion = \"fixed\"\ntilt = \"prescribed\"\n"
                                "misalignment = { y = { time = [\"0 s\", \"5 ms\"], value = [\"0 mrad\", \"1.42 mrad\"] } }\n"));
  EXPECT_EQ(m.outer_ring.tilt, RingTilt::prescribed);
  EXPECT_TRUE(m.outer_ring.misalignment_x.is_zero());
  EXPECT_NEAR(m.outer_ring.misalignment_y(1.0), 1.42e-3, 1e-15);
  EXPECT_NEAR(m.outer_ring.misalignment_y.derivative(0.001), 1.42e-3 / 5e-3, 1e-9);
}

TEST(SpatialScene, MoreRules) {
  // grid: two integers
  EXPECT_EQ(error_of(spatial("", "[contact.ball_race]\ngrid = [5]\n")).key(), "contact.ball_race.grid");
  EXPECT_NE(error_of(spatial("", "[contact.ball_race]\ngrid = [5, 2.5]\n")).reason().find("expected an integer"),
            std::string::npos);
  // rolling resistance needs a film
  EXPECT_EQ(error_of(spatial("", "[contact.ball_race]\nrolling_resistance = true\n")).key(),
            "contact.ball_race.rolling_resistance");
  // the pocket contact has no grid; line-contact laws are not point-contact laws
  EXPECT_EQ(error_of(spatial("", "[contact.ball_cage]\ngrid = [5, 5]\n")).key(), "contact.ball_cage.grid");
  EXPECT_NE(error_of(spatial("", "[contact.ball_race]\nnormal = \"palmgren\"\n"))
                .reason()
                .find("unknown normal law 'palmgren'; known: hertz ('palmgren' is for line contacts"),
            std::string::npos);
  EXPECT_EQ(error_of(spatial("", "[contact.cage_land]\nnormal = \"hertz\"\n")).key(), "contact.cage_land.normal");
  // lubricant and cage sanity limits
  EXPECT_EQ(error_of(spatial("", "[lubricant]\nviscosity = \"0.03 Pa s\"\nlimiting_shear_coefficient = 0.7\n")).key(),
            "lubricant.limiting_shear_coefficient");
  EXPECT_EQ(error_of(spatial("pocket_clearance = \"0.4 mm\"", "pocket_clearance = \"2 mm\"")).key(),
            "cage.pocket_clearance");
  EXPECT_EQ(error_of(spatial("pocket_clearance = \"0.4 mm\"", "pocket_clearance = \"0.4 mm\"\nwidth = \"5 mm\"")).key(),
            "cage.width");
  EXPECT_EQ(error_of(spatial("pocket_clearance = \"0.4 mm\"", "pocket_clearance = \"0.4 mm\"\nsupport = {}")).key(),
            "cage.support");
  // a disturbed start must leave the cage clear of its pockets (ball-guided) and of its land; the
  // unbalance has a sanity limit; neither is a planar cage's
  EXPECT_EQ(error_of(spatial("pocket_clearance = \"0.4 mm\"", "pocket_clearance = \"0.4 mm\"\ninitial_offset = \"0.2 mm\""))
                .key(),
            "cage.initial_offset");
  EXPECT_EQ(error_of(spatial("guidance = \"rolling_element\"",
                             "guidance = \"outer_land\"\nland_clearance = \"0.1 mm\"\ninitial_offset = \"0.1 mm\""))
                .key(),
            "cage.initial_offset");
  const Scene offset = parse(spatial("guidance = \"rolling_element\"",
                                     "guidance = \"outer_land\"\nland_clearance = \"0.1 mm\"\ninitial_offset = \"50 um\"\n"
                                     "mass_eccentricity = \"20 um\""));
  EXPECT_DOUBLE_EQ(offset.cage.initial_offset, 50e-6);
  EXPECT_DOUBLE_EQ(offset.cage.mass_eccentricity, 20e-6);
  EXPECT_EQ(error_of(spatial("pocket_clearance = \"0.4 mm\"", "pocket_clearance = \"0.4 mm\"\nmass_eccentricity = \"2 mm\""))
                .key(),
            "cage.mass_eccentricity");
  EXPECT_EQ(error_of(edited("material = \"brass\"", "material = \"brass\"\ninitial_offset = \"10 um\"")).key(),
            "cage.initial_offset");
  // a land-guided cage must clear the land it rides on
  EXPECT_EQ(error_of(spatial("guidance = \"rolling_element\"",
                             "guidance = \"outer_land\"\nland_clearance = \"0.1 mm\"\nouter_diameter = \"89.9 mm\""))
                .key(),
            "cage.outer_diameter");
  // conformity upper limit, four-point arc angle in range
  EXPECT_EQ(error_of(spatial("outer_conformity = 0.53", "outer_conformity = 0.65")).key(), "bearing.outer_conformity");
  const Scene fp = parse(spatial("type = \"deep_groove_ball\"",
                                 "type = \"four_point_contact_ball\"\narc_contact_angle = \"0.6 rad\""));
  EXPECT_EQ(fp.bearing.type, BearingType::four_point_contact_ball);
  EXPECT_DOUBLE_EQ(fp.bearing.ball.arc_contact_angle, 0.6);
  // ball bearing keys on a roller bearing
  EXPECT_EQ(error_of(edited("roller_diameter = \"6 mm\"", "roller_diameter = \"6 mm\"\ninner_conformity = 0.52")).key(),
            "bearing.inner_conformity");
  EXPECT_EQ(error_of(edited("translation = \"free\"", "translation = \"free\"\ntilt = \"free\"")).key(),
            "inner_ring.tilt");
  // a tilt-free ring may carry tilting moments and a tilt support; both rings tilting freely is not held
  EXPECT_NO_THROW(parse(spatial("load = { fy = \"-1000 N\" }", "load = { fy = \"-1000 N\", mx = \"1 N m\" }\ntilt = \"free\"")));
  EXPECT_EQ(error_of(spatial("load = { fy = \"-1000 N\" }\n[outer_ring]\nmotion = \"fixed\"",
                             "tilt = \"free\"\n[outer_ring]\nmotion = \"free\"\ntilt = \"free\"\n"
                             "support = { stiffness = \"1e8 N/m\", axial_stiffness = \"1e8 N/m\" }"))
                .key(),
            "outer_ring.tilt");
  // a support on a fixed ring, a support without any stiffness
  EXPECT_EQ(error_of(spatial("motion = \"fixed\"\n", "motion = \"fixed\"\nsupport = { stiffness = \"1e8 N/m\" }\n")).key(),
            "outer_ring.support");
  EXPECT_EQ(error_of(spatial("load = { fy = \"-1000 N\" }", "load = { fy = \"-1000 N\" }\nsupport = {}")).key(),
            "inner_ring.support");
  // an axial force needs an axially free ring
  EXPECT_EQ(error_of(spatial("load = { fy = \"-1000 N\" }", "load = { fy = \"-1000 N\", fz = \"100 N\" }\naxial = \"fixed\"")).key(),
            "inner_ring.load.fz");
}

}  // namespace
}  // namespace raceway::scene

namespace raceway::scene {
namespace {

using namespace test;

// ---- units, sane ranges and their override ----------------------------------------------------

TEST(SceneUnits, BareNumbersOnlyForPlainKeysAndZero) {
  // A dimensional key with a bare number is refused and shown in its unit form ...
  const SceneError e = error_of(edited("speed = \"1500 rpm\"", "speed = 1500"));
  EXPECT_EQ(e.key(), "inner_ring.speed");
  EXPECT_NE(e.reason().find("\"1500 rpm\""), std::string::npos) << e.reason();
  // ... also inside a time function's table;
  EXPECT_EQ(error_of(edited("speed = \"1500 rpm\"", "speed = { time = [0, 0.01], value = [\"0 rpm\", \"1500 rpm\"] }"))
                .key(),
            "inner_ring.speed.time");
  // 0 is the same in every unit; plain numbers stay plain.
  const Scene s = parse(edited("radial_clearance = \"0 mm\"", "radial_clearance = 0"));
  EXPECT_EQ(s.bearing.radial_clearance, 0.0);
  const Scene ramp = parse(edited("speed = \"1500 rpm\"", "speed = { time = [0, \"10 ms\"], value = [0, \"1500 r/min\"] }"));
  EXPECT_NEAR(ramp.inner_ring.speed(0.01), 1500 * pi / 30, 1e-12);
  EXPECT_EQ(ramp.inner_ring.speed(0.0), 0.0);
}

TEST(SceneUnits, OutOfRangeValuesNeedTheirKeyNamed) {
  const std::string fast = edited("speed = \"1500 rpm\"", "speed = \"2e6 rpm\"");
  const SceneError e = error_of(fast);
  EXPECT_EQ(e.key(), "inner_ring.speed");
  EXPECT_NE(e.reason().find("allow_out_of_range = [\"inner_ring.speed\"]"), std::string::npos) << e.reason();
  // Named: accepted as written (finite, and within the key's own bounds).
  const std::string allowed = replaced(fast, "model = \"planar\"", "model = \"planar\"\nallow_out_of_range = [\"inner_ring.speed\"]");
  EXPECT_NEAR(parse(allowed).inner_ring.speed(0.0), 2e6 * pi / 30, 1e-3);
  // A time function's parts are covered by its key.
  const std::string long_ramp = edited("speed = \"1500 rpm\"",
                                       "speed = { time = [\"0 s\", \"1e6 s\"], value = [\"0 rpm\", \"1500 rpm\"] }");
  EXPECT_EQ(error_of(long_ramp).key(), "inner_ring.speed.time");
  EXPECT_NO_THROW(parse(replaced(long_ramp, "model = \"planar\"",
                                 "model = \"planar\"\nallow_out_of_range = [\"inner_ring.speed\"]")));
  // Names must be keys of the file, and strings.
  EXPECT_EQ(error_of(edited("model = \"planar\"", "model = \"planar\"\nallow_out_of_range = [\"inner_ring.speeed\"]"))
                .key(),
            "scene.allow_out_of_range");
  EXPECT_EQ(error_of(edited("model = \"planar\"", "model = \"planar\"\nallow_out_of_range = [3]")).key(),
            "scene.allow_out_of_range");
  // Overflow is never allowed.
  EXPECT_NE(error_of(replaced(allowed, "\"2e6 rpm\"", "\"1e308 rev/ms\"")).reason().find("overflows"), std::string::npos);
}

TEST(SceneUnits, KeyLinesNameWhereEachKeyIs) {
  const Scene s = default_scene();
  const std::string& text = s.text;
  const auto line_of_text = [&](std::string_view needle) {
    const auto pos = text.find(needle);
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
  };
  EXPECT_EQ(s.line_of("scene.end_time"), line_of_text("end_time = "));
  EXPECT_EQ(s.line_of("inner_ring.speed"), line_of_text("speed = \"1500 rpm\""));
  EXPECT_EQ(s.line_of("inner_ring.load.fy"), line_of_text("load = {"));
  EXPECT_EQ(s.line_of("contact.cage_land.friction_coefficient"), line_of_text("friction_coefficient = 0.05"));
  EXPECT_EQ(s.line_of("output.max_size"), 0);  // not in the text: a default
}

}  // namespace
}  // namespace raceway::scene
