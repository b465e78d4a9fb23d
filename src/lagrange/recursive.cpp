// A tree's M(q) and bias forces by its recursions in symbols (detail/recursive.hpp).
//
// Spatial vectors are in world coordinates about the world origin O (Plücker coordinates):
// a motion (w, v) is an angular velocity w and the velocity v of the body point at O; a force
// (n, f) is a moment n about O and a force f. A body of mass m, first moment h = m c and
// inertia I_O about O (I_O = R I_C Rᵀ + m (|c|² 1 − c cᵀ)) has the momentum
//   I (w, v) = (I_O w + h × v,  m v − h × w).
// A turn about the unit world axis z through the point o moves as S = (z, o × z), a slide
// along z as S = (0, z). With the joints' rates q̇ and q̈ = 0 (Featherstone 2008, §5.3):
//   V_b = V_parent + Σ_j S_j q̇_j,   A_b = A_parent + Σ_j (V_j⁻ × S_j) q̇_j,
// V_j⁻ the velocity of the frame joint j turns in; the body's force F_b = I_b A_b + V_b ×* I_b V_b
// and the composite force Fc_b = F_b + Σ_children Fc; then f_j = −S_j · Fc_b(j) is the
// Coriolis and centrifugal force. Gravity g acts on the composite mass m_C and first moment
// h_C below the joint: f_j = S_j · (h_C × g, m_C g). And M_ij = S_i · (I_C(j) S_j) for the
// joints i on the path to joint j (composite-rigid-body algorithm, §6.2).
#include "detail/recursive.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "rigid/common/error.hpp"

namespace rigid::lagrange::detail {
namespace {

using GiNaC::ex;

constexpr std::array<const char*, 3> kAxis = {"x", "y", "z"};

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
ex dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 plus(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 scaled(const Vec3& a, const ex& k) { return {a[0] * k, a[1] * k, a[2] * k}; }
Vec3 vec(const Eigen::Vector3d& v) { return {number(v.x()), number(v.y()), number(v.z())}; }

// A spatial motion (w, v) or force (n, f), world coordinates about O.
struct Spatial {
  Vec3 a{0, 0, 0}, b{0, 0, 0};
};

Spatial plus(const Spatial& x, const Spatial& y) { return {plus(x.a, y.a), plus(x.b, y.b)}; }
Spatial scaled(const Spatial& x, const ex& k) { return {scaled(x.a, k), scaled(x.b, k)}; }
// motion × motion: (w₁, v₁) × (w₂, v₂) = (w₁ × w₂, w₁ × v₂ + v₁ × w₂)
Spatial cross_motion(const Spatial& x, const Spatial& y) {
  return {cross(x.a, y.a), plus(cross(x.a, y.b), cross(x.b, y.a))};
}
// motion ×* force: (w, v) ×* (n, f) = (w × n + v × f, w × f)
Spatial cross_force(const Spatial& x, const Spatial& y) {
  return {plus(cross(x.a, y.a), cross(x.b, y.b)), cross(x.a, y.b)};
}
// motion · force: w · n + v · f (power)
ex power(const Spatial& motion, const Spatial& force) {
  return dot(motion.a, force.a) + dot(motion.b, force.b);
}

// A spatial inertia about O: mass, first moment h = m c, rotational inertia I_O (symmetric).
struct Inertia {
  ex m = 0;
  Vec3 h{0, 0, 0};
  Mat3 I{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
};

Spatial apply(const Inertia& in, const Spatial& x) {
  Spatial out;
  const Vec3 Iw = mat_vec(in.I, x.a);
  out.a = plus(Iw, cross(in.h, x.b));
  out.b = plus(scaled(x.b, in.m), cross(x.a, in.h));  // m v − h × w = m v + w × h
  return out;
}

// Names the intermediates: each non-trivial expression becomes a symbol defined by it.
class Namer {
 public:
  Namer(std::vector<GiNaC::symbol>& aux, std::vector<ex>& defs, const std::set<std::string>& taken)
      : aux_(aux), defs_(defs), taken_(taken) {}

  // `e` expanded; a number, a symbol or ±sin/cos of a symbol stays as it is, anything else
  // becomes the intermediate `name` (a suffix _ where the name is taken)
  ex operator()(std::string name, const ex& e) {
    const ex value = e.expand();
    if (trivial(value)) return value;
    while (taken_.count(name) || used_.count(name)) name += "_";
    used_.insert(name);
    aux_.emplace_back(name, tex(name));
    defs_.push_back(value);
    return aux_.back();
  }
  Vec3 operator()(const std::string& name, const Vec3& v) {
    Vec3 out;
    for (int k = 0; k < 3; ++k) out[k] = (*this)(name + "_" + kAxis[k], v[k]);
    return out;
  }
  Mat3 operator()(const std::string& name, const Mat3& A) {
    Mat3 out;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out[i][j] = (*this)(name + "_" + kAxis[i] + kAxis[j], A[i][j]);
    return out;
  }
  // a symmetric matrix: the upper triangle named, the lower one mirrored
  Mat3 symmetric(const std::string& name, const Mat3& A) {
    Mat3 out;
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) {
        out[i][j] = out[j][i] = (*this)(name + "_" + kAxis[i] + kAxis[j], A[i][j]);
      }
    }
    return out;
  }
  Spatial operator()(const std::string& a, const std::string& b, const Spatial& x) {
    return {(*this)(a, x.a), (*this)(b, x.b)};
  }

 private:
  static bool trivial(const ex& e) {
    using namespace GiNaC;
    if (is_a<numeric>(e) || is_a<symbol>(e)) return true;
    if (is_a<function>(e)) return is_a<symbol>(e.op(0));
    if (is_a<mul>(e) && e.nops() == 2) {
      return is_a<numeric>(e.op(1)) && (is_a<symbol>(e.op(0)) || is_a<function>(e.op(0)));
    }
    return false;
  }
  // "R_link3_xy" → \mathrm{R}_{link3,xy}
  static std::string tex(const std::string& name) {
    const auto u = name.find('_');
    if (u == std::string::npos) return "\\mathrm{" + name + "}";
    std::string sub = name.substr(u + 1);
    std::string escaped;
    for (char c : sub) escaped += c == '_' ? std::string(",") : std::string(1, c);
    return "\\mathrm{" + name.substr(0, u) + "}_{\\mathrm{" + escaped + "}}";
  }

  std::vector<GiNaC::symbol>& aux_;
  std::vector<ex>& defs_;
  const std::set<std::string>& taken_;
  std::set<std::string> used_;
};

Mat3 transpose(const Mat3& A) {
  Mat3 T;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T[i][j] = A[j][i];
  return T;
}

// One body's frame in the world: R_WB, p_WB (named), and the joints it carries.
struct Kinematics {
  Mat3 R;
  Vec3 p;
  Spatial V, A;               // velocity and (q̈ = 0, no gravity) acceleration
  std::vector<Spatial> S;     // per joint of the body: its motion subspace
  Inertia body, composite;
  Spatial force, composite_force;
};

// The frame and the joints of body `b`, from its parent's frame `P` (nullptr: the world).
// Each joint's frame (R, p before it turns or slides) is named, so that its axis z, a point o
// on it and the axis's moment o × z stay short expressions of named ones.
void forward(const System::Impl& s, Namer& name, const TreeBody& b, const Kinematics* P,
             Kinematics& K) {
  Mat3 R = P ? P->R : identity3();
  Vec3 p = P ? P->p : Vec3{0, 0, 0};
  Spatial V = P ? P->V : Spatial{};
  Spatial A = P ? P->A : Spatial{};
  // X_PB = Trans(position) · orientation · J₁ ⋯ J_m
  p = plus(p, mat_vec(R, b.position));
  R = mat_mul(R, b.orientation);
  for (const TreeJoint& J : b.joints) {
    const std::string& coord = s.coord_names[J.coordinate];
    R = name("Rj_" + coord, R);
    p = name("pj_" + coord, p);
    const ex qd = s.qd[J.coordinate];
    Spatial S;
    if (J.turn) {
      S.a = name("z_" + coord, mat_vec(R, vec(J.axis)));
      const Vec3 o = name("o_" + coord, plus(p, mat_vec(R, vec(J.anchor))));
      S.b = name("u_" + coord, cross(o, S.a));  // o × z: the axis's moment about O
      const Mat3 RJ = rodrigues(J.axis, s.q[J.coordinate]);
      const Vec3 a = vec(J.anchor);
      const Vec3 RJa = mat_vec(RJ, a);
      p = plus(p, mat_vec(R, {a[0] - RJa[0], a[1] - RJa[1], a[2] - RJa[2]}));
      R = mat_mul(R, RJ);
    } else {
      S.b = name("z_" + coord, mat_vec(R, vec(J.axis)));
      p = plus(p, scaled(S.b, s.q[J.coordinate]));
    }
    // the frame the joint turns in moves with V (V_j⁻): A gains (V_j⁻ × S_j) q̇_j
    A = plus(A, scaled(cross_motion(V, S), qd));
    V = plus(V, scaled(S, qd));
    K.S.push_back(S);
  }
  K.R = name("R_" + b.name, R);
  K.p = name("p_" + b.name, p);
  K.V = name("w_" + b.name, "v_" + b.name, V);
  K.A = name("aw_" + b.name, "av_" + b.name, A);
}

// The body's inertia about O from its mass, COM and inertia about the COM in B.
Inertia body_inertia(Namer& name, const TreeBody& b, const Kinematics& K) {
  Inertia in;
  in.m = b.mass;
  const Vec3 c = name("c_" + b.name, plus(K.p, mat_vec(K.R, b.com)));
  in.h = scaled(c, b.mass);
  // I_O = R I_C Rᵀ + m (|c|² 1 − c cᵀ)
  const Mat3 IW = mat_mul(mat_mul(K.R, b.inertia), transpose(K.R));
  Mat3 IO;
  const ex c2 = dot(c, c);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) IO[i][j] = IW[i][j] + b.mass * ((i == j ? c2 : ex(0)) - c[i] * c[j]);
  }
  in.I = name.symmetric("Io_" + b.name, IO);
  return in;
}

// ----------------------------------------------------------------------------------------
// inverse dynamics in body coordinates

// A frame C placed on a frame P: C's axes in P (E = R_PC) and C's origin in P (r).
struct Step {
  Mat3 E;
  Vec3 r;
};

// A motion in P's coordinates (about P's origin) in C's: w_C = Eᵀ w, v_C = Eᵀ (v + w × r).
Spatial motion_to_child(const Step& X, const Spatial& m) {
  return {mat_t_vec(X.E, m.a), mat_t_vec(X.E, plus(m.b, cross(m.a, X.r)))};
}

// A force in C's coordinates (about C's origin) in P's: f_P = E f, n_P = E n + r × f_P.
Spatial force_to_parent(const Step& X, const Spatial& F) {
  const Vec3 f = mat_vec(X.E, F.b);
  return {plus(mat_vec(X.E, F.a), cross(X.r, f)), f};
}

}  // namespace

TreeInverseDynamics tree_inverse_dynamics(const System::Impl& s,
                                          const std::vector<TreeBody>& bodies,
                                          const Vec3& gravity,
                                          const std::set<std::string>& taken) {
  TreeInverseDynamics out;
  Namer name(out.aux, out.defs, taken);
  out.tau.assign(static_cast<std::size_t>(s.n), 0);
  struct Frame {
    std::vector<Step> steps;     // the fixed placement, then one per joint
    std::vector<Spatial> S;      // per joint: its motion in the frame after it
    std::vector<std::size_t> c;  // per joint: its coordinate
    Spatial V, A, F;             // in the body's frame; F: the subtree's force on the body
  };
  std::vector<Frame> B(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const TreeBody& body = bodies[b];
    Frame& f = B[b];
    // the world "accelerates" by −g, so that the forces include the weights [Featherstone2008 §5.3]
    Spatial V, A{{0, 0, 0}, {-gravity[0], -gravity[1], -gravity[2]}};
    if (body.parent >= 0) {
      V = B[static_cast<std::size_t>(body.parent)].V;
      A = B[static_cast<std::size_t>(body.parent)].A;
    }
    f.steps.push_back({body.orientation, body.position});
    V = motion_to_child(f.steps.back(), V);
    A = motion_to_child(f.steps.back(), A);
    for (const TreeJoint& J : body.joints) {
      const std::string& coord = s.coord_names[J.coordinate];
      Step X;
      Spatial S;
      const Vec3 a = vec(J.axis);
      if (J.turn) {
        // a turn about a through o: C = P turned, its origin at o − E o; S = (a, o × a)
        X.E = rodrigues(J.axis, s.q[J.coordinate]);
        const Vec3 o = vec(J.anchor);
        const Vec3 Eo = mat_vec(X.E, o);
        X.r = {o[0] - Eo[0], o[1] - Eo[1], o[2] - Eo[2]};
        S = {a, cross(o, a)};
      } else {
        X.E = identity3();
        X.r = scaled(a, s.q[J.coordinate]);
        S = {{0, 0, 0}, a};
      }
      const ex qd = s.qd[J.coordinate];
      V = plus(motion_to_child(X, V), scaled(S, qd));
      A = plus(plus(motion_to_child(X, A), scaled(S, s.qdd[J.coordinate])),
               scaled(cross_motion(V, S), qd));
      V = name("idw_" + coord, "idv_" + coord, V);
      A = name("ida_" + coord, "idal_" + coord, A);
      f.steps.push_back(X);
      f.S.push_back(S);
      f.c.push_back(J.coordinate);
    }
    f.V = V;
    f.A = A;
    // the body's inertia about its origin: m, first moment h = m c, I_O = I_C + m(|c|² 1 − c cᵀ)
    Inertia in;
    in.m = body.mass;
    in.h = scaled(body.com, body.mass);
    const ex c2 = dot(body.com, body.com);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        in.I[i][j] = body.inertia[i][j] +
                     body.mass * ((i == j ? c2 : ex(0)) - body.com[i] * body.com[j]);
      }
    }
    const Spatial momentum = name("idpa_" + body.name, "idpl_" + body.name, apply(in, V));
    f.F = plus(apply(in, A), cross_force(V, momentum));
  }
  // backward: each joint's force, and the subtree's force into the parent (children come later)
  for (std::size_t b = bodies.size(); b-- > 0;) {
    Frame& f = B[b];
    Spatial F = name("idn_" + bodies[b].name, "idf_" + bodies[b].name, f.F);
    for (std::size_t j = f.S.size(); j-- > 0;) {
      out.tau[f.c[j]] = power(f.S[j], F).expand();
      F = force_to_parent(f.steps[j + 1], F);
      if (j > 0) F = name("idn_" + s.coord_names[f.c[j]], "idf_" + s.coord_names[f.c[j]], F);
    }
    F = force_to_parent(f.steps[0], F);
    if (bodies[b].parent >= 0) {
      Frame& P = B[static_cast<std::size_t>(bodies[b].parent)];
      P.F = plus(P.F, F);
    }
  }
  return out;
}

TreeEquations tree_equations(System::Impl& s, const std::vector<TreeBody>& bodies,
                             const Vec3& gravity, const std::set<std::string>& taken) {
  const auto n = static_cast<std::size_t>(s.n);
  Namer name(s.aux, s.aux_def, taken);
  std::vector<Kinematics> K(bodies.size());
  TreeEquations out;
  out.T = 0;
  out.V = 0;
  // forward: frames, velocities, accelerations, each body's inertia, momentum and force
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const TreeBody& B = bodies[b];
    RIGID_ASSERT(B.parent < static_cast<int>(b));
    forward(s, name, B, B.parent < 0 ? nullptr : &K[static_cast<std::size_t>(B.parent)], K[b]);
    K[b].body = body_inertia(name, B, K[b]);
    const Spatial momentum = name("pa_" + B.name, "pl_" + B.name, apply(K[b].body, K[b].V));
    out.T += power(K[b].V, momentum) / 2;
    for (int k = 0; k < 3; ++k) out.V -= K[b].body.h[k] * gravity[k];
    K[b].force = plus(apply(K[b].body, K[b].A), cross_force(K[b].V, momentum));
    out.poses.emplace_back(K[b].p, K[b].R);
  }
  // backward: composite inertias and forces, children into parents (children come later)
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    K[b].composite = K[b].body;
    K[b].composite_force = K[b].force;
  }
  for (std::size_t b = bodies.size(); b-- > 0;) {
    const TreeBody& B = bodies[b];
    Kinematics& k = K[b];
    const bool leaf = std::none_of(bodies.begin() + static_cast<std::ptrdiff_t>(b) + 1, bodies.end(),
                                   [&](const TreeBody& o) { return o.parent == static_cast<int>(b); });
    if (!leaf) {  // a leaf's composite is its own inertia, already named
      k.composite.m = name("mC_" + B.name, k.composite.m);
      k.composite.h = name("hC_" + B.name, k.composite.h);
      k.composite.I = name.symmetric("IoC_" + B.name, k.composite.I);
    }
    k.composite_force = name("nC_" + B.name, "fC_" + B.name, k.composite_force);
    if (B.parent >= 0) {
      Kinematics& P = K[static_cast<std::size_t>(B.parent)];
      P.composite.m += k.composite.m;
      P.composite.h = plus(P.composite.h, k.composite.h);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) P.composite.I[i][j] += k.composite.I[i][j];
      P.composite_force = plus(P.composite_force, k.composite_force);
    }
  }
  // per joint: the bias forces, and its column of M against the joints on its path
  out.M.assign(n * n, 0);
  out.inertial.assign(n, 0);
  out.gravity.assign(n, 0);
  // the joints on the path from the root to each body, in order: (coordinate, S)
  std::vector<std::vector<std::pair<std::size_t, Spatial>>> path(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].parent >= 0) path[b] = path[static_cast<std::size_t>(bodies[b].parent)];
    for (std::size_t j = 0; j < bodies[b].joints.size(); ++j) path[b].emplace_back(bodies[b].joints[j].coordinate, K[b].S[j]);
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Kinematics& k = K[b];
    const Spatial weight{cross(k.composite.h, gravity), scaled(gravity, k.composite.m)};
    const std::size_t first = path[b].size() - bodies[b].joints.size();
    for (std::size_t j = 0; j < bodies[b].joints.size(); ++j) {
      const std::size_t c = bodies[b].joints[j].coordinate;
      const Spatial& S = k.S[j];
      out.inertial[c] += -power(S, k.composite_force);
      out.gravity[c] += power(S, weight);
      const Spatial F = name("Fn_" + s.coord_names[c], "Ff_" + s.coord_names[c], apply(k.composite, S));
      for (std::size_t i = 0; i <= first + j; ++i) {
        const std::size_t r = path[b][i].first;
        const ex Mij = power(path[b][i].second, F).expand();
        out.M[r * n + c] += Mij;
        if (r != c) out.M[c * n + r] += Mij;
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    out.inertial[i] = out.inertial[i].expand();
    out.gravity[i] = out.gravity[i].expand();
  }
  out.T = out.T.expand();
  out.V = out.V.expand();
  return out;
}

}  // namespace rigid::lagrange::detail
