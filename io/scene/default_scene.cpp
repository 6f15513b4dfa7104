// raceway default scene: the built-in scene text (identical to jobs/scenes/default.toml).
#include "io/scene/scene_parser.hpp"

namespace raceway::scene {

namespace {
constexpr const char* kDefaultScene = R"TOML(# raceway default scene: a small cylindrical roller bearing that runs in seconds.
#
# Units: a quantity is a string "<number> <unit>", e.g. "6 mm", "1500 rpm", "208 GPa", "5 N s/m",
# "0.02 1/GPa"; a bare number is a plain number (0.3), or 0. "Hz" means revolutions per second.
# Copy this file and edit it; `raceway check FILE` validates a scene without running it.

# [scene]: what to simulate and for how long.
[scene]
name = "default"               # label stored in the output
model = "planar"               # "planar" (roller bearings in the radial plane) or "spatial" (ball bearings)
end_time = "0.1 s"             # simulated time
output_interval = "0.5 ms"     # time between stored samples (<= end_time)
gravity = false                # gravity along -y

# [bearing]: geometry of a cylindrical roller bearing.
[bearing]
type = "cylindrical_roller"
rolling_elements = 8           # number of rollers
roller_diameter = "6 mm"
roller_length = "6 mm"         # effective contact length
pitch_diameter = "30 mm"       # diameter of the circle through the roller centres
radial_clearance = "0 mm"      # diametral clearance P_d
# inner_bore_diameter = "18 mm"      # default: inner race diameter - roller diameter
# outer_outside_diameter = "42 mm"   # default: outer race diameter + roller diameter
# ring_width = "6 mm"                # default: roller_length
roller_material = "steel"
ring_material = "steel"

# [materials.NAME]: steel, brass and polyamide are built in; a section adds or replaces one, e.g.
# [materials.bronze]
# density = "8800 kg/m^3"
# youngs_modulus = "110 GPa"
# poisson_ratio = 0.34

# [cage]: a brass cage guided on the inner ring's land.
[cage]
guidance = "inner_land"        # "inner_land" | "outer_land" | "rolling_element"
pocket_clearance = "0.2 mm"    # pocket width minus roller diameter
land_clearance = "0.3 mm"      # radial play between cage and guiding land
material = "brass"

# [inner_ring]: driven at a constant speed, centre free to move under the load.
# A ramp would be: speed = { time = ["0 s", "0.02 s"], value = ["0 rpm", "1500 rpm"] }
[inner_ring]
motion = "driven"              # "fixed" | "driven" | "free"
speed = "1500 rpm"
translation = "free"           # the centre moves in x and y
load = { fx = "0 N", fy = "-500 N" }

# [outer_ring]: held in the housing.
[outer_ring]
motion = "fixed"

# [contact.*]: contact laws, here at their default values.
# Roller-race: Palmgren line contact, Hunt-Crossley damping, tanh traction.
[contact.roller_race]
normal = "palmgren"
slices = 1
crown_drop = "0 mm"
damping = "hunt_crossley"
damping_factor = "0.5 s/m"
traction = "tanh"
friction_coefficient = 0.1
slip_velocity_scale = "0.05 m/s"

# Roller-cage pocket contact.
[contact.roller_cage]
normal = "palmgren"
damping = "hunt_crossley"
damping_factor = "0.5 s/m"
traction = "tanh"
friction_coefficient = 0.1
slip_velocity_scale = "0.05 m/s"

# Cage-land contact (land-guided cages).
[contact.cage_land]
normal = "palmgren"
damping = "hunt_crossley"
damping_factor = "0.5 s/m"
traction = "tanh"
friction_coefficient = 0.05
slip_velocity_scale = "0.05 m/s"

# [solver]: CVODE settings.
[solver]
method = "bdf"                 # "bdf" | "adams"
rtol = 1e-6
# atol = { position = "1e-9 m", angle = "1e-6 rad", velocity = "1e-6 m/s", angular_velocity = "1e-3 rad/s" }
#   (unset: chosen from the physical scales)
linear_solver = "auto"         # "auto" | "petsc-bordered" | "block-elimination" | "sundials-dense"
# petsc_options = "-fieldsplit_1_pc_factor_mat_solver_type mumps"   # for petsc-bordered

# [output]: what is written besides the state.
[output]
segments = true                # per-segment diagnostics
)TOML";
}  // namespace

std::string default_scene_text() { return kDefaultScene; }

}  // namespace raceway::scene
