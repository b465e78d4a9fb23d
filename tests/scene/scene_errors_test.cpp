// Every refusal of a malformed scene names its place in the file (file:line:col) and speaks in
// the scene's terms: no raw library text (toml++, GiNaC, CLN, std::optional, allocation), no
// C++ function names. The scenes are made here by mutating each line of two valid scenes:
// every value replaced by values of the wrong type, non-finite, negative, zero, huge, empty or
// malformed; every key renamed to an unknown one; every line removed.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {
namespace {

constexpr std::string_view kCoordinates = R"toml(gravity = [0, 0, -9.81]
[parameters]
m = 2.0
l = "0.5*m"
[[coordinates]]
name = "theta"
initial = 0.3
velocity = 0
[[bodies]]
name = "rod"
primitive = "solid_cylinder"
radius = 0.01
height = "l"
mass = "m"
position = ["l/2*sin(theta)", 0, "-l/2*cos(theta)"]
rotation = [{axis = [0, 1, 0], angle = "theta"}]
[[bodies]]
name = "tip"
point_masses = [{mass = 0.1, position = [0, 0, 0]}]
position = ["l*sin(theta)", 0, "-l*cos(theta)"]
[[potentials]]
expression = "0.5*theta^2"
[[forces]]
coordinate = "theta"
expression = "-0.1*theta_dot"
[[velocity_constraints]]
name = "hold"
coefficients = {theta = "1 + theta^2"}
term = "0*theta"
[[springs]]
body_a = "tip"
point_a = [0, 0, 0]
stiffness = 10
rest_length = 0.1
[simulation]
t_end = 1.0
integrator = "rk4"
dt = 1e-3
output_dt = 0.1
tolerance = 1e-9
[output]
directory = "out/x"
formats = ["csv", "npy"]
quantities = ["theta*"]
max_memory = "1GiB"
)toml";

constexpr std::string_view kFreeBodies = R"toml(gravity = [0, 0, -9.81]
[parameters]
rho = 1000
[[bodies]]
name = "box"
free = true
primitive = "box"
size = [0.1, 0.2, 0.3]
density = "rho"
initial_position = [0, 0, 1]
initial_velocity = [1, 0, 0]
angular_velocity = [0, 1, 0.1]
initial_rotation = {axis = [0, 0, 1], angle = 0.5}
[[bodies]]
name = "top"
free = true
inertia = {mass = 1, com = [0, 0, 0.1], ixx = 0.01, iyy = 0.01, izz = 0.02}
pivot = [0, 0, 0]
initial_quaternion = [1, 0, 0, 0]
angular_velocity = [0, 0, 10]
[simulation]
t_end = 1.0
integrator = "splitting4"
dt = 1e-3
output_dt = 0.01
)toml";

// "((…(1)…))" as a TOML string, `depth` levels deep (appended in place: GCC 12 warns wrongly
// about the overlap of a chain of + on temporaries, -Wrestrict)
std::string nested_ones(std::size_t depth) {
  std::string s = "\"";
  s.append(depth, '(');
  s += '1';
  s.append(depth, ')');
  s += '"';
  return s;
}

// Values that each key should refuse (or accept) without a crash, with a location.
const std::vector<std::string> kBadValues = {
    "\"abc\"", "[1, 2]", "{a = 1}", "true", "nan", "inf", "-inf", "-1.0", "0", "-1",
    "9007199254740993", "-9223372036854775808", "1e308", "\"1/0\"", "\"log(0)\"", "\"9^9^9\"",
    "\"0^0\"", "\"\"", "\"((((\"", "\"sqrt(-1)\"", "\"exp(-1e300*1e-10)\"", "1979-05-27",
    "[]", "{}", "\"x\"", "\"t\"", "[[1]]", nested_ones(300)};

std::vector<std::string> lines_of(std::string_view text) {
  std::vector<std::string> lines;
  std::istringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

// The malformed variants of a scene.
std::vector<std::string> mutations(std::string_view base) {
  const std::vector<std::string> lines = lines_of(base);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    std::vector<std::string> changed = lines;
    changed.erase(changed.begin() + static_cast<std::ptrdiff_t>(i));  // the line removed
    out.push_back(join(changed));
    const auto eq = line.find(" = ");
    if (eq == std::string::npos) {
      // a table header: an unknown key right under it, and an empty table
      changed = lines;
      changed.insert(changed.begin() + static_cast<std::ptrdiff_t>(i) + 1, "colour = 3");
      out.push_back(join(changed));
      continue;
    }
    changed = lines;
    changed[i] = "x" + line;  // an unknown key
    out.push_back(join(changed));
    for (const std::string& v : kBadValues) {
      changed = lines;
      changed[i] = line.substr(0, eq + 3) + v;
      out.push_back(join(changed));
      // inside arrays and inline tables too: the first number replaced
      const auto digit = line.find_first_of("0123456789", eq);
      if (digit != std::string::npos && (line.find('[') != std::string::npos || line.find('{') != std::string::npos)) {
        changed[i] = line.substr(0, digit) + v + line.substr(line.find_first_not_of("0123456789.e-", digit));
        out.push_back(join(changed));
      }
    }
  }
  return out;
}

struct Refusal {
  std::string scene;
  std::string message;
};

// Runs the scene as `rigid check` does (load, build, check) and returns the error, if any.
std::optional<std::string> refusal_of(const std::filesystem::path& file) {
  try {
    const Model model = load_model(file);
    model.check();
  } catch (const Cancelled& e) {
    return std::string("cancelled: ") + e.what();
  } catch (const Error& e) {
    return std::string(e.what());
  } catch (const std::exception& e) {
    return std::string("NOT A rigid::Error: ") + e.what();
  }
  return std::nullopt;
}

// "FILE:LINE:COL: text": the file, two runs of digits and a non-blank message (checked by hand:
// std::regex trips GCC 12's -Wmaybe-uninitialized under the sanitizers)
bool is_located(std::string_view msg, std::string_view file) {
  if (!msg.starts_with(file)) return false;
  std::size_t i = file.size();
  for (int field = 0; field < 2; ++field) {
    if (i >= msg.size() || msg[i] != ':') return false;
    const std::size_t start = ++i;
    while (i < msg.size() && msg[i] >= '0' && msg[i] <= '9') ++i;
    if (i == start) return false;
  }
  return msg.substr(i).starts_with(": ") && msg.size() > i + 2 && msg[i + 2] != ' ';
}

void check_all(std::string_view base, const std::string& name, std::size_t& refused) {
  const auto dir = std::filesystem::temp_directory_path() / ("rigid_scene_errors_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "m.toml";
  const std::vector<std::string> raw = {"bad optional", "bad_alloc", "std::", "log_eval", "floating point",
                                        "power::eval", "(): ", "toml::", "Error while parsing", "nan kg", "terminate"};
  std::vector<Refusal> bad;
  for (const std::string& text : mutations(base)) {
    std::ofstream(file) << text;
    const auto msg = refusal_of(file);
    if (!msg) continue;
    ++refused;
    bool ok = is_located(*msg, file.string());
    for (const auto& r : raw) ok = ok && msg->find(r) == std::string::npos;
    if (!ok || std::getenv("RIGID_PRINT_REFUSALS") != nullptr) bad.push_back({text, *msg});
  }
  for (const Refusal& r : bad) ADD_FAILURE() << "message: " << r.message << "\nscene:\n" << r.scene;
  std::filesystem::remove_all(dir);
}

TEST(SceneErrors, EveryRefusalOfAMalformedSceneIsLocatedAndWorded) {
  std::size_t refused = 0;
  check_all(kCoordinates, "coordinates", refused);
  check_all(kFreeBodies, "free", refused);
  // the mutations are refusals in their great majority (a count, so that a broken generator
  // that makes only valid scenes cannot pass)
  EXPECT_GT(refused, 1000u);
}

// The check of the test itself: a place needs the file, a line, a column and a message.
TEST(SceneErrors, TheLocationCheckNeedsLineColumnAndMessage) {
  EXPECT_TRUE(is_located("/t/m.toml:3:14: mass is negative", "/t/m.toml"));
  EXPECT_FALSE(is_located("/t/m.toml: mass is negative", "/t/m.toml"));
  EXPECT_FALSE(is_located("/t/m.toml:3: mass is negative", "/t/m.toml"));
  EXPECT_FALSE(is_located("/t/m.toml:3:x: mass is negative", "/t/m.toml"));
  EXPECT_FALSE(is_located("/t/m.toml:3:14:", "/t/m.toml"));
  EXPECT_FALSE(is_located("/t/other.toml:3:14: mass is negative", "/t/m.toml"));
  EXPECT_FALSE(is_located("mass is negative", "/t/m.toml"));
}

// The two bases are valid: the refusals above come from the mutations.
TEST(SceneErrors, TheBaseScenesAreValid) {
  EXPECT_NO_THROW(Model(parse_scene(kCoordinates, "c.toml")).check());
  EXPECT_NO_THROW(Model(parse_scene(kFreeBodies, "f.toml")).check());
}

}  // namespace
}  // namespace rigid::scene
