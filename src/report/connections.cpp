#include "report/detail/connections.hpp"

#include <algorithm>
#include <cmath>

namespace rigid::report::detail {
namespace {

// A distance is constant when no frame departs from the first frame's by more than this share
// of it: the poses of a body posed by expressions are exact functions of the coordinates, so a
// rod's length varies by round-off (1e-15 relative), or by the 10 significant digits of a
// trajectory read back from CSV; a body that merely passes near another varies by far more.
constexpr double kConstantShare = 1e-6;

// The largest departure of |a(t) − b(t)| from its first value, and that value.
std::pair<double, double> distance_spread(const std::vector<Eigen::Vector3d>& a,
                                          const std::vector<Eigen::Vector3d>& b) {
  const double d0 = (a.front() - b.front()).norm();
  double spread = 0;
  for (std::size_t f = 1; f < a.size(); ++f) {
    spread = std::max(spread, std::abs((a[f] - b[f]).norm() - d0));
  }
  return {d0, spread};
}

double travel(const std::vector<Eigen::Vector3d>& p) {
  double out = 0;
  for (const Eigen::Vector3d& x : p) out = std::max(out, (x - p.front()).norm());
  return out;
}

double turn(const std::vector<Eigen::Quaterniond>& q) {
  double out = 0;
  for (const Eigen::Quaterniond& x : q) out = std::max(out, x.angularDistance(q.front()));
  return out;
}

}  // namespace

std::vector<Link> find_links(const scene::Model& model, const std::vector<BodyPoses>& poses) {
  const scene::Scene& sc = model.scene();
  const std::size_t n = model.bodies().size();
  std::vector<Link> links;
  if (poses.size() != n || n == 0 || poses.front().p_WB.empty()) return links;

  // the size of the scene: the largest distance of any body origin from the world origin or
  // travelled; what counts as "does not move" is a 1e-9 share of it
  double scale = 0;
  for (const BodyPoses& b : poses) {
    for (const Eigen::Vector3d& p : b.p_WB) scale = std::max(scale, p.norm());
  }
  const double still = 1e-9 * std::max(scale, 1e-300);

  // a body the scene connects by a spring or a rope: that is what is drawn, not a rod found
  // from its motion (two particles on a spinning spring stay at one distance)
  auto named = [&](const std::string& name) {
    const auto on = [&](const auto& ends) { return ends.body_a == name || ends.body_b == name; };
    return std::any_of(sc.springs.begin(), sc.springs.end(), on) ||
           std::any_of(sc.ropes.begin(), sc.ropes.end(), on);
  };

  for (std::size_t i = 0; i < n; ++i) {
    const scene::Body& b = sc.bodies[i];
    const scene::ModelBody& mb = model.bodies()[i];
    const BodyPoses& pose = poses[i];
    if (b.free) {
      // a top: a rod from its pivot (fixed in the world where it starts) to its COM
      if (b.pivot) {
        const Eigen::Vector3d pivot_B((*b.pivot)[0], (*b.pivot)[1], (*b.pivot)[2]);
        links.push_back({i, mb.mass.com(), std::nullopt,
                         pose.p_WB.front() + pose.R_WB.front() * pivot_B, "pivot"});
      }
      continue;
    }
    if (!b.parent.empty()) {
      // the body's end: the anchor of its last joint when that is a turn (a point the turn leaves
      // where it is, so the same point of the body frame and of the frame before it)
      auto attachment = [](const scene::Body& body) -> Eigen::Vector3d {
        if (!body.joints.empty() && body.joints.back().kind == scene::Joint::Kind::kTurn) {
          const auto& a = body.joints.back().anchor;
          return {a[0], a[1], a[2]};
        }
        return Eigen::Vector3d::Zero();
      };
      for (std::size_t j = 0; j < n; ++j) {
        if (sc.bodies[j].name == b.parent) {
          links.push_back({i, attachment(b), j, attachment(sc.bodies[j]), "parent"});
          break;
        }
      }
      continue;
    }
    if (named(b.name)) continue;
    if (travel(pose.p_WB) > still) {
      // a rod to the nearest earlier body whose origin stays at one distance, else to the world
      // origin when that distance is constant
      bool found = false;
      for (std::size_t j = i; j-- > 0 && !found;) {
        const auto [d0, spread] = distance_spread(pose.p_WB, poses[j].p_WB);
        if (d0 > still && spread <= kConstantShare * d0) {
          links.push_back(
              {i, Eigen::Vector3d::Zero(), j, Eigen::Vector3d::Zero(), "constant distance"});
          found = true;
        }
      }
      if (!found) {
        const std::vector<Eigen::Vector3d> origin(pose.p_WB.size(), Eigen::Vector3d::Zero());
        const auto [d0, spread] = distance_spread(pose.p_WB, origin);
        if (d0 > still && spread <= kConstantShare * d0) {
          links.push_back({i, Eigen::Vector3d::Zero(), std::nullopt, Eigen::Vector3d::Zero(),
                           "constant distance"});
        }
      }
    } else if (turn(pose.R_WB) > 1e-9 && mb.mass.com().norm() > still) {
      // turning about a fixed origin with the COM elsewhere: a pivot there, a rod to the COM
      links.push_back({i, mb.mass.com(), std::nullopt, pose.p_WB.front(), "fixed origin"});
    }
  }

  // the springs and the constraints' ropes, as the scene gives their ends
  auto index_of = [&](const std::string& name) -> std::optional<std::size_t> {
    for (std::size_t j = 0; j < n; ++j) {
      if (sc.bodies[j].name == name) return j;
    }
    return std::nullopt;
  };
  auto add_ends = [&](const auto& ends, const char* rule) {
    const std::optional<std::size_t> a = index_of(ends.body_a);
    const std::optional<std::size_t> b =
        ends.body_b.empty() ? std::nullopt : index_of(ends.body_b);
    if (!a || (!ends.body_b.empty() && !b)) return;  // the scene's check names them
    const auto& pa = ends.point_a;
    const auto& pb = ends.point_b;
    links.push_back({*a, {pa[0], pa[1], pa[2]}, b, {pb[0], pb[1], pb[2]}, rule});
  };
  for (const scene::Spring& sp : sc.springs) add_ends(sp, "spring");
  for (const scene::Rope& r : sc.ropes) add_ends(r, "rope");
  return links;
}

}  // namespace rigid::report::detail
