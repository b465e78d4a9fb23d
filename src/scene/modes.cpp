#include "rigid/scene/modes.hpp"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/common/escape.hpp"
#include "rigid/common/error.hpp"

namespace rigid::scene {
namespace {

using Json = nlohmann::ordered_json;

Json matrix(const Eigen::MatrixXd& A) {
  Json rows = Json::array();
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    Json row = Json::array();
    for (Eigen::Index j = 0; j < A.cols(); ++j) row.push_back(A(i, j));
    rows.push_back(std::move(row));
  }
  return rows;
}

Json complex(std::complex<double> z) { return Json{{"re", z.real()}, {"im", z.imag()}}; }

}  // namespace

std::vector<lagrange::PointValue> point_values(const Model& model, const std::vector<std::string>& at) {
  std::vector<lagrange::PointValue> out;
  for (const std::string& a : at) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == a.size()) {
      throw Error(fmt::format("point '{}' is not of the form name=value (a coordinate, or "
                              "<cyclic coordinate>_dot, and its value)",
                              a));
    }
    const std::string name = a.substr(0, eq);
    const double value = lagrange::evaluate_constant(lagrange::Expression(a.substr(eq + 1)),
                                                     model.parameters(), fmt::format("point '{}'", a));
    out.push_back({name, value});
  }
  return out;
}

lagrange::NormalModes normal_modes(const Model& model, const std::vector<std::string>& at) {
  if (model.kind() != SceneKind::kCoordinates) {
    throw Error(fmt::format("{}: normal modes are of a scene of [[coordinates]]; this scene is "
                            "made of free bodies, whose state is a pose and a twist rather than "
                            "coordinates (pose the bodies by [[coordinates]] to linearise them)",
                            model.scene().file.string()));
  }
  lagrange::LinearizeOptions options;
  options.at = point_values(model, at);
  return lagrange::normal_modes(model.system(), options);
}

std::string modes_json(const lagrange::NormalModes& r, const std::string& scene_file) {
  Json j;
  j["scene"] = escaped(scene_file);  // any bytes (0xff) as \xNN: the JSON writer needs UTF-8
  j["coordinates"] = r.coordinate_names;
  j["ignorable"] = r.ignorable_names;
  Json q = Json::object(), qd = Json::object();
  for (std::size_t i = 0; i < r.coordinate_names.size(); ++i) {
    q[r.coordinate_names[i]] = r.q[static_cast<Eigen::Index>(i)];
    qd[r.coordinate_names[i]] = r.q_dot[static_cast<Eigen::Index>(i)];
  }
  j["point"] = Json{{"q", q}, {"q_dot", qd}};
  j["searched"] = r.searched;
  j["iterations"] = r.iterations;
  j["residual"] = r.residual;
  j["stability"] = lagrange::to_string(r.stability);
  j["gyroscopic"] = r.gyroscopic;
  j["constraints"] = r.constraint_names;
  Json multipliers = Json::object();
  for (std::size_t k = 0; k < r.constraint_names.size(); ++k) {
    multipliers[r.constraint_names[k]] = r.lambda[static_cast<Eigen::Index>(k)];
  }
  j["multipliers"] = multipliers;
  j["M"] = matrix(r.M);
  j["C"] = matrix(r.C);
  j["K"] = matrix(r.K);
  j["reduced"] = Json{{"coordinates", r.reduced_names}, {"M", matrix(r.M_reduced)},
                      {"C", matrix(r.C_reduced)}, {"K", matrix(r.K_reduced)},
                      {"tangent_basis", matrix(r.tangent_basis)}};
  Json ev = Json::array();
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) ev.push_back(complex(r.eigenvalues[k]));
  j["eigenvalues"] = ev;
  Json modes = Json::array();
  for (const lagrange::Mode& m : r.modes) {
    Json md;
    md["omega"] = m.omega;
    md["hz"] = m.hz;
    md["omega_squared"] = std::isnan(m.omega_squared) ? Json(nullptr) : Json(m.omega_squared);
    md["growth_rate"] = m.growth_rate;
    md["eigenvalue"] = complex(m.eigenvalue);
    md["stability"] = lagrange::to_string(m.stability);
    Json shape = Json::object();
    for (std::size_t i = 0; i < r.coordinate_names.size(); ++i) {
      shape[r.coordinate_names[i]] = complex(m.shape[static_cast<Eigen::Index>(i)]);
    }
    md["shape"] = shape;
    modes.push_back(std::move(md));
  }
  j["modes"] = modes;
  return j.dump(2) + "\n";
}

}  // namespace rigid::scene
