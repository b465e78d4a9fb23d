#include "rigid/io/inertial_xml.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>

#include <fmt/format.h>
#include <tinyxml2.h>

#include "detail/fix_geometry.hpp"
#include "detail/inertial_element.hpp"
#include "detail/xml_numbers.hpp"
#include "detail/xml_parse.hpp"
#include "rigid/common/error.hpp"
#include "rigid/lie/euler.hpp"
#include "rigid/lie/so3.hpp"

namespace rigid::io {
namespace {

// A problem with one inertial: recorded in the entry, not thrown, so that `check` can list
// every bad inertial of a file.
struct EntryProblem {
  std::string text;
};

// expected = 0 is not used here: every attribute has its count
std::vector<double> parse_numbers(const char* text, std::size_t expected, const std::string& what) {
  detail::XmlNumbers n = detail::read_xml_numbers(text, expected, what, false);
  if (!n.problem.empty()) throw EntryProblem{std::move(n.problem)};
  return std::move(n.values);
}

Eigen::Vector3d vec3(const std::vector<double>& v, std::size_t offset = 0) {
  return Eigen::Vector3d(v[offset], v[offset + 1], v[offset + 2]);
}

double required_number(const tinyxml2::XMLElement* e, const char* attribute,
                       const std::string& element) {
  const char* text = e->Attribute(attribute);
  if (text == nullptr) {
    throw EntryProblem{fmt::format("<{}> has no attribute '{}'", element, attribute)};
  }
  return parse_numbers(text, 1, fmt::format("<{}> attribute '{}'", element, attribute))[0];
}

Eigen::Matrix3d tensor(double xx, double yy, double zz, double xy, double xz, double yz) {
  Eigen::Matrix3d I;
  I << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  return I;
}

void read_urdf(const tinyxml2::XMLElement* inertial, InertialEntry& entry) {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (const auto* origin = inertial->FirstChildElement("origin")) {
    if (const char* t = origin->Attribute("xyz")) xyz = vec3(parse_numbers(t, 3, "<origin> attribute 'xyz'"));
    if (const char* t = origin->Attribute("rpy")) rpy = vec3(parse_numbers(t, 3, "<origin> attribute 'rpy'"));
  }
  const auto* mass = inertial->FirstChildElement("mass");
  if (mass == nullptr) throw EntryProblem{"<inertial> has no <mass> element"};
  entry.mass = required_number(mass, "value", "mass");
  const auto* in = inertial->FirstChildElement("inertia");
  if (in == nullptr) throw EntryProblem{"<inertial> has no <inertia> element"};
  const Eigen::Matrix3d I_in =
      tensor(required_number(in, "ixx", "inertia"), required_number(in, "iyy", "inertia"),
             required_number(in, "izz", "inertia"), required_number(in, "ixy", "inertia"),
             required_number(in, "ixz", "inertia"), required_number(in, "iyz", "inertia"));
  // the tensor is given in the inertial frame (rotated by rpy): re-express in the link frame
  const Eigen::Matrix3d R = rotation_from_rpy(rpy);
  entry.com = xyz;
  entry.inertia_com = R * I_in * R.transpose();
}

void read_mjcf(const tinyxml2::XMLElement* inertial, InertialEntry& entry) {
  for (const char* unsupported : {"axisangle", "euler", "xyaxes", "zaxis"}) {
    if (inertial->Attribute(unsupported) != nullptr) {
      throw EntryProblem{fmt::format("orientation attribute '{}' is not supported (its meaning "
                                     "depends on <compiler> settings); use quat=\"w x y z\"",
                                     unsupported)};
    }
  }
  const char* pos = inertial->Attribute("pos");
  if (pos == nullptr) throw EntryProblem{"<inertial> has no attribute 'pos'"};
  entry.com = vec3(parse_numbers(pos, 3, "<inertial> attribute 'pos'"));
  SO3d q = SO3d::identity();
  if (const char* t = inertial->Attribute("quat")) {
    const auto v = parse_numbers(t, 4, "<inertial> attribute 'quat'");
    // MJCF order: w x y z
    const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (!(norm >= 1e-12) || !std::isfinite(norm)) {
      throw EntryProblem{fmt::format("<inertial> attribute 'quat': expected a non-zero "
                                     "quaternion, got '{}'", t)};
    }
    q = SO3d::from_quaternion(v[0], v[1], v[2], v[3]);  // normalised, as MuJoCo does
  }
  entry.mass = required_number(inertial, "mass", "inertial");
  const char* diag = inertial->Attribute("diaginertia");
  const char* full = inertial->Attribute("fullinertia");
  if ((diag == nullptr) == (full == nullptr)) {
    throw EntryProblem{"<inertial> needs exactly one of 'diaginertia' and 'fullinertia'"};
  }
  Eigen::Matrix3d I_in;
  if (diag != nullptr) {
    const auto v = parse_numbers(diag, 3, "<inertial> attribute 'diaginertia'");
    I_in = Eigen::Vector3d(v[0], v[1], v[2]).asDiagonal();
  } else {
    // MJCF order: xx yy zz xy xz yz
    const auto v = parse_numbers(full, 6, "<inertial> attribute 'fullinertia'");
    I_in = tensor(v[0], v[1], v[2], v[3], v[4], v[5]);
  }
  const Eigen::Matrix3d R = q.matrix();
  entry.inertia_com = R * I_in * R.transpose();
}

double sdf_child(const tinyxml2::XMLElement* parent, const char* name, double fallback) {
  const auto* e = parent->FirstChildElement(name);
  if (e == nullptr) return fallback;
  return parse_numbers(e->GetText(), 1, fmt::format("<{}>", name))[0];
}

void read_sdf(const tinyxml2::XMLElement* inertial, InertialEntry& entry) {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (const auto* pose = inertial->FirstChildElement("pose")) {
    if (pose->Attribute("relative_to") != nullptr) {
      throw EntryProblem{"<pose relative_to=...> of an inertial is not supported; give the pose "
                         "in the link frame"};
    }
    const auto v = parse_numbers(pose->GetText(), 6, "<pose>");
    xyz = vec3(v, 0);
    rpy = vec3(v, 3);
  }
  entry.mass = sdf_child(inertial, "mass", 1.0);  // SDF defaults
  Eigen::Matrix3d I_in = Eigen::Matrix3d::Identity();
  if (const auto* in = inertial->FirstChildElement("inertia")) {
    I_in = tensor(sdf_child(in, "ixx", 1.0), sdf_child(in, "iyy", 1.0), sdf_child(in, "izz", 1.0),
                  sdf_child(in, "ixy", 0.0), sdf_child(in, "ixz", 0.0), sdf_child(in, "iyz", 0.0));
  }
  const Eigen::Matrix3d R = rotation_from_rpy(rpy);
  entry.com = xyz;
  entry.inertia_com = R * I_in * R.transpose();
}

// every <inertial> below `e` in document order (not inside another <inertial>); MJCF
// through its followed <include>s
void collect(const tinyxml2::XMLElement* e, InertialFormat format, const std::string& source,
             const detail::MjcfDocument* mjcf, std::vector<InertialEntry>& out) {
  const auto children = mjcf != nullptr ? mjcf->children(e) : [e] {
    std::vector<const tinyxml2::XMLElement*> all;
    for (const auto* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
      all.push_back(c);
    }
    return all;
  }();
  for (const auto* child : children) {
    if (std::string_view(child->Name()) == "inertial") {
      const char* name = e->Attribute("name");
      out.push_back(detail::read_inertial_element(child, format, name == nullptr ? "" : name,
                                                  mjcf != nullptr ? mjcf->file_of(child) : source));
    } else {
      collect(child, format, source, mjcf, out);
    }
  }
}

const tinyxml2::XMLElement* parse_root(tinyxml2::XMLDocument& doc, const std::string& xml,
                                       const std::string& source) {
  detail::parse_xml(doc, xml, source);
  return doc.RootElement();
}

InertialFormat format_of(const tinyxml2::XMLElement* root, const std::string& source) {
  const std::string_view name = root->Name();
  if (name == "robot") return InertialFormat::urdf;
  if (name == "mujoco") return InertialFormat::mjcf;
  if (name == "sdf") return InertialFormat::sdf;
  rigid::detail::throw_error_at(SourceLocation{source, root->GetLineNum(), 0},
                         fmt::format("unknown root element <{}>; expected <robot> (URDF), "
                                     "<mujoco> (MJCF) or <sdf> (SDF)",
                                     name));
}

std::string num(double v) { return fmt::format("{}", v); }

std::string vec(const Eigen::Vector3d& v) {
  return fmt::format("{} {} {}", v.x() + 0.0, v.y() + 0.0, v.z() + 0.0);  // no "-0"
}

}  // namespace

const char* to_string(InertialFormat format) {
  switch (format) {
    case InertialFormat::urdf: return "urdf";
    case InertialFormat::mjcf: return "mjcf";
    case InertialFormat::sdf: return "sdf";
  }
  return "?";
}

// URDF/SDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll), the extrinsic X-Y-Z sequence of rigid::lie
// (at gimbal lock it sets the first angle, roll, to 0)
Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy) {
  return from_euler(rpy, EulerConvention::parse("XYZ", false)).matrix();
}

Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R) {
  return to_euler(SO3d::from_matrix(R), EulerConvention::parse("XYZ", false));
}

std::string write_inertial_document(const MassProperties& mp, InertialFormat format,
                                    const InertialWriteOptions& options,
                                    const std::optional<Eigen::Matrix3d>& inertial_frame) {
  RIGID_REQUIRE(!options.name.empty() &&
                    options.name.find_first_of("<>&\"'") == std::string::npos,
                "name must be non-empty and free of XML special characters (<>&\"'), got '{}'",
                options.name);
  const Eigen::Vector3d& c = mp.com();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d I = mp.inertia_com();
  if (options.principal && inertial_frame) {
    R = SO3d::from_matrix(*inertial_frame).matrix();  // checks it is a rotation
    const Eigen::Matrix3d I_in = R.transpose() * mp.inertia_com() * R;
    const double off = std::max({std::abs(I_in(0, 1)), std::abs(I_in(0, 2)), std::abs(I_in(1, 2))});
    RIGID_REQUIRE(off <= MassProperties::kRelativeTolerance * I_in.trace(),
                  "the given inertial frame is not a principal frame: the inertia expressed in it "
                  "has an off-diagonal element of {} kg·m² (above {} · tr I = {} kg·m²)",
                  off, MassProperties::kRelativeTolerance, MassProperties::kRelativeTolerance * I_in.trace());
    I = I_in.diagonal().asDiagonal();
  } else if (options.principal) {
    const PrincipalAxes pa = mp.principal_axes();
    R = pa.R_BP;
    I = pa.moments.asDiagonal();
  }
  const std::string& n = options.name;
  switch (format) {
    case InertialFormat::urdf:
      return fmt::format(
          "<?xml version=\"1.0\"?>\n"
          "<robot name=\"{0}\">\n"
          "  <link name=\"{0}\">\n"
          "    <inertial>\n"
          "      <origin xyz=\"{1}\" rpy=\"{2}\"/>\n"
          "      <mass value=\"{3}\"/>\n"
          "      <inertia ixx=\"{4}\" ixy=\"{5}\" ixz=\"{6}\" iyy=\"{7}\" iyz=\"{8}\" izz=\"{9}\"/>\n"
          "    </inertial>\n"
          "  </link>\n"
          "</robot>\n",
          n, vec(c), vec(rpy_from_rotation(R)), num(mp.mass()), num(I(0, 0)), num(I(0, 1)),
          num(I(0, 2)), num(I(1, 1)), num(I(1, 2)), num(I(2, 2)));
    case InertialFormat::mjcf: {
      std::string inertia;
      if (options.principal) {
        const SO3d q = SO3d::from_matrix(R);
        inertia = fmt::format("quat=\"{} {} {} {}\" diaginertia=\"{} {} {}\"", q.w(), q.x(), q.y(),
                              q.z(), I(0, 0), I(1, 1), I(2, 2));
      } else {
        inertia = fmt::format("fullinertia=\"{} {} {} {} {} {}\"", I(0, 0), I(1, 1), I(2, 2),
                              I(0, 1), I(0, 2), I(1, 2));
      }
      return fmt::format(
          "<mujoco model=\"{0}\">\n"
          "  <worldbody>\n"
          "    <body name=\"{0}\">\n"
          "      <inertial pos=\"{1}\" mass=\"{2}\" {3}/>\n"
          "    </body>\n"
          "  </worldbody>\n"
          "</mujoco>\n",
          n, vec(c), num(mp.mass()), inertia);
    }
    case InertialFormat::sdf:
      return fmt::format(
          "<?xml version=\"1.0\"?>\n"
          "<sdf version=\"1.7\">\n"
          "  <model name=\"{0}\">\n"
          "    <link name=\"{0}\">\n"
          "      <inertial>\n"
          "        <pose>{1} {2}</pose>\n"
          "        <mass>{3}</mass>\n"
          "        <inertia>\n"
          "          <ixx>{4}</ixx>\n"
          "          <ixy>{5}</ixy>\n"
          "          <ixz>{6}</ixz>\n"
          "          <iyy>{7}</iyy>\n"
          "          <iyz>{8}</iyz>\n"
          "          <izz>{9}</izz>\n"
          "        </inertia>\n"
          "      </inertial>\n"
          "    </link>\n"
          "  </model>\n"
          "</sdf>\n",
          n, vec(c), vec(rpy_from_rotation(R)), num(mp.mass()), num(I(0, 0)), num(I(0, 1)),
          num(I(0, 2)), num(I(1, 1)), num(I(1, 2)), num(I(2, 2)));
  }
  RIGID_THROW("unknown format");
}

MassProperties InertialEntry::mass_properties() const {
  if (problem) {
    RIGID_THROW("inertial of '{}' (line {}) is not usable: {}", name, line, *problem);
  }
  return MassProperties(mass, com, inertia_com);
}

InertialFormat detect_inertial_format(const std::string& xml, const std::string& source) {
  tinyxml2::XMLDocument doc;
  return format_of(parse_root(doc, xml, source), source);
}

std::vector<InertialEntry> read_inertials(const std::string& xml, const std::string& source) {
  tinyxml2::XMLDocument doc;
  const auto* root = parse_root(doc, xml, source);
  const InertialFormat format = format_of(root, source);
  std::vector<InertialEntry> out;
  if (format == InertialFormat::mjcf) {
    const detail::MjcfDocument mjcf(root, source, true);
    collect(root, format, source, &mjcf, out);
  } else {
    collect(root, format, source, nullptr, out);
  }
  return out;
}

std::vector<InertialEntry> read_inertials_file(const std::string& path) {
  // refuses a FIFO or device before opening it (opening a FIFO blocks until a writer comes)
  return read_inertials(detail::read_model_file(path), path);
}

namespace detail {

InertialEntry read_inertial_element(const tinyxml2::XMLElement* inertial, InertialFormat format,
                                    std::string name, std::string file) {
  InertialEntry entry;
  entry.name = std::move(name);
  entry.file = std::move(file);
  entry.line = inertial->GetLineNum();
  try {
    switch (format) {
      case InertialFormat::urdf: read_urdf(inertial, entry); break;
      case InertialFormat::mjcf: read_mjcf(inertial, entry); break;
      case InertialFormat::sdf: read_sdf(inertial, entry); break;
    }
    entry.problem = MassProperties::check(entry.mass, entry.com, entry.inertia_com);
  } catch (const EntryProblem& p) {
    entry.problem = p.text;
  }
  return entry;
}

}  // namespace detail

}  // namespace rigid::io
