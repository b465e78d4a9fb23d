#pragma once
// Small scenes several tests run (scene files as text; parse_scene or a temporary file).
namespace rigid::test {

/// A thin rod of mass m and length L pivoted at its end, swinging in the x–z plane from
/// θ(0) = 1 rad at rest: E = ½ (m L²/3) θ̇² − m g (L/2) cos θ. rk4 at dt = 1e-3 s for 2 s, a row
/// every 0.01 s. Parameters g, m, L and the coordinate θ can be overridden by name.
inline constexpr const char* kRodPendulum = R"toml(
gravity = [0, 0, "-g"]
[parameters]
g = 9.81
m = 0.5
L = 1.0
[[coordinates]]
name = "theta"
initial = 1.0
[[bodies]]
name = "rod"
primitive = "thin_rod"
length = "L"
mass = "m"
position = ["-(L/2)*sin(theta)", 0, "-(L/2)*cos(theta)"]
rotation = [{axis = [0, 1, 0], angle = "theta"}]  # R_y(theta) e_z points from the COM to the pivot
[simulation]
t_end = 2
integrator = "rk4"
dt = 1e-3
output_dt = 0.01
)toml";

}  // namespace rigid::test
