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
#include <optional>

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
  // per column of the body's joints (a hinge or slide has one, a ball three): its motion
  // subspace, its velocity's index, and V and A of the frame it turns in (V_j⁻, A_j⁻)
  std::vector<Spatial> S;
  std::vector<std::size_t> column;
  std::vector<Spatial> V_in, A_in;
  // per column: the index in S of its joint's first column, and whether the joint is a ball
  std::vector<std::size_t> first;
  std::vector<bool> ball;
  Inertia body, composite;
  Spatial force, composite_force;
};

// The name of joint J in intermediates' names: its coordinate's (a ball's own name).
std::string joint_name(const System::Impl& s, const TreeJoint& J) {
  if (J.ball) {
    for (const System::Impl::Ball& b : s.balls) {
      if (b.q == J.quaternion) return b.name;
    }
  }
  return s.coord_names[static_cast<std::size_t>(s.q_of_v[J.coordinate])];
}

// The name of the ball whose first velocity is v.
const std::string& ball_name(const System::Impl& s, std::size_t v) {
  const auto b = std::find_if(s.balls.begin(), s.balls.end(),
                              [&](const System::Impl::Ball& ball) { return ball.v == v; });
  RIGID_ASSERT(b != s.balls.end());
  return b->name;
}

// The name of velocity v in intermediates' names: its coordinate's, a ball's b_wx b_wy b_wz.
std::string column_name(const System::Impl& s, std::size_t v) {
  const int q = s.q_of_v[v];
  return q >= 0 ? s.coord_names[static_cast<std::size_t>(q)] : s.velocity_names[v];
}

// The coordinate of a hinge's or slide's amount.
const GiNaC::symbol& joint_coordinate(const System::Impl& s, const TreeJoint& J) {
  return s.q[static_cast<std::size_t>(s.q_of_v[J.coordinate])];
}

// The rotation of a ball's quaternion q = (w, x, y, z), named: with σ = 2/|q|² (named),
//   R = 1 + σ (w [v]× + [v]×²),  v = (x, y, z),
// a rotation for every q ≠ 0 (the unit quaternion's matrix when |q| = 1), so that the
// equations hold along a run whose quaternion drifts off the unit sphere by round-off.
Mat3 ball_rotation(const System::Impl& s, Namer& name, const TreeJoint& J, const std::string& nm) {
  const ex w = s.q[J.quaternion], x = s.q[J.quaternion + 1], y = s.q[J.quaternion + 2],
           z = s.q[J.quaternion + 3];
  const ex sigma = name("sq_" + nm, 2 / (w * w + x * x + y * y + z * z));
  return name("Rq_" + nm, Mat3{{{1 - sigma * (y * y + z * z), sigma * (x * y - w * z), sigma * (x * z + w * y)},
                                {sigma * (x * y + w * z), 1 - sigma * (x * x + z * z), sigma * (y * z - w * x)},
                                {sigma * (x * z - w * y), sigma * (y * z + w * x), 1 - sigma * (x * x + y * y)}}});
}

// The frame and the joints of body `b`, from its parent's frame `P` (nullptr: the world).
// Each joint's frame (R, p before it turns or slides) is named, so that its axis z, a point o
// on it and the axis's moment o × z stay short expressions of named ones. A ball's three
// columns are the body's axes R e_k through its anchor o, (R e_k, o × R e_k). They move with
// the body, Ṡ_k = V⁺ × S_k, but only their sum enters A: Σ_k Ṡ_k ω_k = V⁺ × S ω = V⁻ × S ω
// (V⁺ = V⁻ + S ω), which is A's term (V_j⁻ × S_j) q̇_j per column with V_j⁻ = V⁻, the velocity
// of the frame before the ball, for all three.
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
    const std::string coord = joint_name(s, J);
    R = name("Rj_" + coord, R);
    p = name("pj_" + coord, p);
    if (J.ball) {
      const Vec3 a = vec(J.anchor);
      const Vec3 o = name("o_" + coord, plus(p, mat_vec(R, a)));
      const Mat3 RJ = ball_rotation(s, name, J, coord);
      const Vec3 RJa = mat_vec(RJ, a);
      p = plus(p, mat_vec(R, {a[0] - RJa[0], a[1] - RJa[1], a[2] - RJa[2]}));
      R = name("Rb_" + coord, mat_mul(R, RJ));
      const Spatial V_before = V, A_before = A;
      const std::size_t first = K.S.size();
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string axis = coord + "_" + kAxis[k];
        Spatial S;
        S.a = {R[0][k], R[1][k], R[2][k]};
        S.b = name("u_" + axis, cross(o, S.a));
        const ex w = s.qd[J.coordinate + k];
        K.V_in.push_back(V_before);
        K.A_in.push_back(A_before);
        A = plus(A, scaled(cross_motion(V_before, S), w));
        V = plus(V, scaled(S, w));
        K.S.push_back(S);
        K.column.push_back(J.coordinate + k);
        K.first.push_back(first);
        K.ball.push_back(true);
      }
      continue;
    }
    const ex qd = s.qd[J.coordinate];
    Spatial S;
    if (J.turn) {
      S.a = name("z_" + coord, mat_vec(R, vec(J.axis)));
      const Vec3 o = name("o_" + coord, plus(p, mat_vec(R, vec(J.anchor))));
      S.b = name("u_" + coord, cross(o, S.a));  // o × z: the axis's moment about O
      const Mat3 RJ = rodrigues(J.axis, joint_coordinate(s, J));
      const Vec3 a = vec(J.anchor);
      const Vec3 RJa = mat_vec(RJ, a);
      p = plus(p, mat_vec(R, {a[0] - RJa[0], a[1] - RJa[1], a[2] - RJa[2]}));
      R = mat_mul(R, RJ);
    } else {
      S.b = name("z_" + coord, mat_vec(R, vec(J.axis)));
      p = plus(p, scaled(S.b, joint_coordinate(s, J)));
    }
    // the frame the joint turns in moves with V (V_j⁻): A gains (V_j⁻ × S_j) q̇_j
    K.V_in.push_back(V);
    K.A_in.push_back(A);
    A = plus(A, scaled(cross_motion(V, S), qd));
    V = plus(V, scaled(S, qd));
    K.first.push_back(K.S.size());
    K.ball.push_back(false);
    K.S.push_back(S);
    K.column.push_back(J.coordinate);
  }
  K.R = name("R_" + b.name, R);
  K.p = name("p_" + b.name, p);
  K.V = name("w_" + b.name, "v_" + b.name, V);
  K.A = name("aw_" + b.name, "av_" + b.name, A);
}

// The body's inertia about O from its mass, COM and inertia about the COM in B. `staged`
// names I_C Rᵀ first, so that R (I_C Rᵀ) costs two 3 × 3 products rather than the expanded
// triple sums (the exported derivatives; the engine's equations keep the expanded form).
Inertia body_inertia(Namer& name, const TreeBody& b, const Kinematics& K, bool staged = false) {
  Inertia in;
  in.m = b.mass;
  const Vec3 c = name("c_" + b.name, plus(K.p, mat_vec(K.R, b.com)));
  in.h = scaled(c, b.mass);
  // I_O = R I_C Rᵀ + m (|c|² 1 − c cᵀ)
  const Mat3 IW = staged ? mat_mul(K.R, name("ICRt_" + b.name, mat_mul(b.inertia, transpose(K.R))))
                         : mat_mul(mat_mul(K.R, b.inertia), transpose(K.R));
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
  // a joint as the body-coordinate recursion takes it: where it puts the frame after it, and
  // its columns there (a hinge's or slide's one, a ball's three) with their velocities' indices
  struct Joint {
    Step X;
    std::vector<Spatial> S;
    std::vector<std::size_t> c;
    std::string name;
  };
  struct Frame {
    Step placement;
    std::vector<Joint> joints;
    Spatial V, A, F;  // in the body's frame; F: the subtree's force on the body
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
    f.placement = {body.orientation, body.position};
    V = motion_to_child(f.placement, V);
    A = motion_to_child(f.placement, A);
    for (const TreeJoint& J : body.joints) {
      Joint j;
      j.name = joint_name(s, J);
      const Vec3 a = vec(J.axis);
      const Vec3 o = vec(J.anchor);
      if (J.ball) {
        // a ball about o: C = P turned by R(q) about o; S_k = (e_k, o × e_k), k = x, y, z
        j.X.E = ball_rotation(s, name, J, "id" + j.name);
        const Vec3 Eo = mat_vec(j.X.E, o);
        j.X.r = {o[0] - Eo[0], o[1] - Eo[1], o[2] - Eo[2]};
        for (std::size_t k = 0; k < 3; ++k) {
          Vec3 e{0, 0, 0};
          e[k] = 1;
          j.S.push_back({e, cross(o, e)});
          j.c.push_back(J.coordinate + k);
        }
      } else if (J.turn) {
        // a turn about a through o: C = P turned, its origin at o − E o; S = (a, o × a)
        j.X.E = rodrigues(J.axis, joint_coordinate(s, J));
        const Vec3 Eo = mat_vec(j.X.E, o);
        j.X.r = {o[0] - Eo[0], o[1] - Eo[1], o[2] - Eo[2]};
        j.S.push_back({a, cross(o, a)});
        j.c.push_back(J.coordinate);
      } else {
        j.X.E = identity3();
        j.X.r = scaled(a, joint_coordinate(s, J));
        j.S.push_back({{0, 0, 0}, a});
        j.c.push_back(J.coordinate);
      }
      // V_C = X V_P + S q̇, A_C = X A_P + S q̈ + V_C × S q̇ (S fixed in C)
      Spatial Sqd, Sqdd;
      for (std::size_t k = 0; k < j.S.size(); ++k) {
        Sqd = plus(Sqd, scaled(j.S[k], s.qd[j.c[k]]));
        Sqdd = plus(Sqdd, scaled(j.S[k], s.qdd[j.c[k]]));
      }
      V = plus(motion_to_child(j.X, V), Sqd);
      A = plus(plus(motion_to_child(j.X, A), Sqdd), cross_motion(V, Sqd));
      V = name("idw_" + j.name, "idv_" + j.name, V);
      A = name("ida_" + j.name, "idal_" + j.name, A);
      f.joints.push_back(std::move(j));
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
    for (std::size_t j = f.joints.size(); j-- > 0;) {
      const Joint& J = f.joints[j];
      for (std::size_t k = 0; k < J.S.size(); ++k) out.tau[J.c[k]] = power(J.S[k], F).expand();
      F = force_to_parent(J.X, F);
      if (j > 0) F = name("idn_" + J.name, "idf_" + J.name, F);
    }
    F = force_to_parent(f.placement, F);
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
  // (per column: a ball's three are three entries)
  std::vector<std::vector<std::pair<std::size_t, Spatial>>> path(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].parent >= 0) path[b] = path[static_cast<std::size_t>(bodies[b].parent)];
    for (std::size_t j = 0; j < K[b].S.size(); ++j) path[b].emplace_back(K[b].column[j], K[b].S[j]);
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Kinematics& k = K[b];
    const Spatial weight{cross(k.composite.h, gravity), scaled(gravity, k.composite.m)};
    const std::size_t first = path[b].size() - k.S.size();
    for (std::size_t j = 0; j < k.S.size(); ++j) {
      const std::size_t c = k.column[j];
      const Spatial& S = k.S[j];
      out.inertial[c] += -power(S, k.composite_force);
      out.gravity[c] += power(S, weight);
      const std::string cn = column_name(s, c);
      const Spatial F = name("Fn_" + cn, "Ff_" + cn, apply(k.composite, S));
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

// ----------------------------------------------------------------------------------------
// ∂τ/∂q and ∂τ/∂q̇ of the inverse dynamics, analytically
//
// World coordinates as in tree_equations, the joints ordered along the tree (j ⪯ i: j is i or
// on the path to it; the joints of one body are joined by massless links). A joint's motion
// S_j moves with every joint before it, ∂S_i/∂q_j = S_j × S_i (j ⪯ i), and so does a body's
// inertia, ∂I_k/∂q_j = S_j ×* I_k − I_k S_j×. With v_k, a_k (q̈ and the world's −g included),
// h_k = I_k v_k and f_k = I_k a_k + v_k ×* h_k as in Newton–Euler, ψ̇_j = v_j⁻ × S_j and
// ψ̈_j = a_j⁻ × S_j + v_j⁻ × ψ̇_j (v_j⁻, a_j⁻: the frame joint j turns in), differentiating
// v_k = Σ S_l q̇_l and a_k = a₀ + Σ (S_l q̈_l + ψ̇_l q̇_l) along the path (Jacobi's identity
// for the products) gives, for a body k below joint j,
//   ∂v_k/∂q_j = S_j × v_k + ψ̇_j,            ∂a_k/∂q_j = S_j × a_k + ψ̈_j + ψ̇_j × v_k,
//   ∂f_k/∂q_j = S_j ×* f_k + I_k ψ̈_j + B_k ψ̇_j,   ∂f_k/∂q̇_j = B_k S_j + 2 I_k ψ̇_j,
// with B_k x = I_k (x × v_k) + x ×* h_k + v_k ×* (I_k x). Summed over the subtree (the
// composites I^C, B^C, F^C of the body carrying the lower joint) and paired with S_i, where
// (S_j × S_i)·F + S_i·(S_j ×* F) = 0 cancels the turning of S_i:
//   j ⪯ i:  ∂τ_i/∂q_j = S_i·(I^C_i ψ̈_j + B^C_i ψ̇_j),   ∂τ_i/∂q̇_j = S_i·(B^C_i S_j + 2 I^C_i ψ̇_j)
//   i ≺ j:  ∂τ_i/∂q_j = S_i·(S_j ×* F^C_j + I^C_j ψ̈_j + B^C_j ψ̇_j),
//           ∂τ_i/∂q̇_j = S_i·(B^C_j S_j + 2 I^C_j ψ̇_j)
// and 0 for joints on different branches (Carpentier and Mansard, "Analytical derivatives of
// rigid body dynamics algorithms", RSS 2018, derive the same in their notation). The pairs
// j ⪯ i need two vectors per joint i, I^C_i S_i and B^C_iᵀ S_i (S_i·I^C x = x·I^C S_i), so
// the assembly is a dot product per pair.
//
// A ball's orientation is perturbed along its tangent, q ⊗ exp(δθ) with δθ in its body's frame
// (MuJoCo's convention): the body turns about its own axes through the anchor, so ∂/∂δθ_k acts
// as S_k × on everything that moves with it, as a hinge's ∂/∂q_k does. Its three columns
// S_k = (R e_k, o × R e_k) are fixed in the body, so each turns with the other two in both
// orders, and all three turn in the frame before the ball (forward()): the formulas hold with
// that frame's v⁻ and a⁻ (q̈ of the joints before the ball only) for each column, and with the
// pairs of one ball's columns taken as j ⪯ i both ways. Since A sees v⁻ × S_k ω_k rather than
// the velocity after the earlier columns, the derivative by ω_j gains the ball's own motion
// Ω = Σ_k S_k ω_k: ∂a_k/∂ω_j = S_j × v_k + χ_j with χ_j = 2 ψ̇_j + Ω × S_j = (2 v⁻ + Ω) × S_j
// (a hinge's χ_j = 2 ψ̇_j), and ∂f_k/∂q̇_j = B_k S_j + I_k χ_j.

namespace {

// A spatial vector's six components (angular or moment first).
const ex& component(const Spatial& x, int m) { return m < 3 ? x.a[m] : x.b[m - 3]; }
Spatial unit_spatial(int m) {
  Spatial e;
  if (m < 3) {
    e.a[m] = 1;
  } else {
    e.b[m - 3] = 1;
  }
  return e;
}
// a 6 × 6 operator by its columns (B e_m)
using Columns = std::array<Spatial, 6>;
Spatial apply_columns(const Columns& B, const Spatial& x) {
  Spatial out;
  for (int m = 0; m < 6; ++m) out = plus(out, scaled(B[m], component(x, m)));
  return out;
}
// the pairing S·(B x) = (Bᵀ S)·x, as the components of Bᵀ S
std::array<ex, 6> transposed_apply(const Columns& B, const Spatial& S) {
  std::array<ex, 6> out;
  for (int m = 0; m < 6; ++m) out[m] = power(S, B[m]);
  return out;
}
ex dot6(const std::array<ex, 6>& y, const Spatial& x) {
  ex sum = 0;
  for (int m = 0; m < 6; ++m) sum += y[m] * component(x, m);
  return sum;
}

}  // namespace

TreeDerivatives tree_inverse_dynamics_derivatives(const System::Impl& s,
                                                  const std::vector<TreeBody>& bodies,
                                                  const Vec3& gravity,
                                                  const std::set<std::string>& taken) {
  const auto n = static_cast<std::size_t>(s.n);
  TreeDerivatives out;
  Namer name(out.aux, out.defs, taken);
  const Spatial a0{{0, 0, 0}, {-gravity[0], -gravity[1], -gravity[2]}};
  struct Joint {
    std::size_t coordinate;
    std::size_t body;
    Spatial S, dS, ddS;  // S_j, ψ̇_j, ψ̈_j
    // a ball's column: the velocity index of its ball's first column, and χ_j
    std::optional<std::size_t> ball;
    Spatial chi;
  };
  std::vector<Joint> joints;
  std::vector<std::vector<std::size_t>> path(bodies.size());  // indices into joints
  std::vector<Kinematics> K(bodies.size());
  std::vector<Spatial> qdd_part(bodies.size());  // Σ S_l q̈_l along the path
  std::vector<Inertia> IC(bodies.size());
  std::vector<Columns> BC(bodies.size());
  // composites: the force at q̈ = 0 (gravity included), the force of q̈, the momentum
  std::vector<Spatial> FC(bodies.size()), GC(bodies.size()), HC(bodies.size());
  // forward: frames, motions, ψ̇, ψ̈; each body's I, h, f and B
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const TreeBody& body = bodies[b];
    RIGID_ASSERT(body.parent < static_cast<int>(b));
    const auto parent = static_cast<std::size_t>(body.parent);
    forward(s, name, body, body.parent < 0 ? nullptr : &K[parent], K[b]);
    Spatial acc = body.parent < 0 ? Spatial{} : qdd_part[parent];
    Spatial acc_joint = acc;  // at the start of the column's joint
    Spatial omega;            // a ball's own motion Ω
    if (body.parent >= 0) path[b] = path[parent];
    for (std::size_t j = 0; j < K[b].S.size(); ++j) {  // per column (a ball's three)
      const std::size_t c = K[b].column[j];
      const std::string coord = column_name(s, c);
      Joint J{c, b, K[b].S[j], {}, {}, {}, {}};
      const Spatial& v_in = K[b].V_in[j];
      if (K[b].first[j] == j) {
        acc_joint = acc;
        if (K[b].ball[j]) {
          const std::size_t first = K[b].column[j];
          omega = {};
          for (std::size_t k = j; k < j + 3; ++k) {
            omega = plus(omega, scaled(K[b].S[k], s.qd[K[b].column[k]]));
          }
          const std::string ball = ball_name(s, first);
          omega = name("dWa_" + ball, "dWb_" + ball, omega);
        }
      }
      const Spatial a_in = plus(plus(K[b].A_in[j], a0), acc_joint);
      J.dS = name("dSa_" + coord, "dSb_" + coord, cross_motion(v_in, J.S));
      J.ddS = name("ddSa_" + coord, "ddSb_" + coord,
                   plus(cross_motion(a_in, J.S), cross_motion(v_in, J.dS)));
      if (K[b].ball[j]) {
        J.ball = K[b].column[K[b].first[j]];
        J.chi = name("dCa_" + coord, "dCb_" + coord,
                     cross_motion(plus(scaled(v_in, 2), omega), J.S));
      }
      // named, so that each use reads six values rather than a sum along the whole path
      acc = name("dQa_" + coord, "dQb_" + coord, plus(acc, scaled(J.S, s.qdd[c])));
      path[b].push_back(joints.size());
      joints.push_back(J);
    }
    qdd_part[b] = acc;
    const Inertia I = body_inertia(name, body, K[b], true);
    const Spatial& v = K[b].V;
    const Spatial a = name("dAa_" + body.name, "dAb_" + body.name, plus(K[b].A, a0));
    const Spatial h = name("dha_" + body.name, "dhb_" + body.name, apply(I, v));
    FC[b] = plus(apply(I, a), cross_force(v, h));
    GC[b] = apply(I, acc);
    HC[b] = h;
    for (int m = 0; m < 6; ++m) {
      const Spatial e = unit_spatial(m);
      BC[b][static_cast<std::size_t>(m)] =
          plus(plus(apply(I, cross_motion(e, v)), cross_force(e, h)), cross_force(v, apply(I, e)));
    }
    IC[b] = I;
  }
  // backward: the composites, children into parents (children come later)
  for (std::size_t b = bodies.size(); b-- > 0;) {
    const std::string& body = bodies[b].name;
    IC[b].m = name("dmC_" + body, IC[b].m);
    IC[b].h = name("dhC_" + body, IC[b].h);
    IC[b].I = name.symmetric("dIC_" + body, IC[b].I);
    FC[b] = name("dFCa_" + body, "dFCb_" + body, FC[b]);
    GC[b] = name("dGCa_" + body, "dGCb_" + body, GC[b]);
    HC[b] = name("dHCa_" + body, "dHCb_" + body, HC[b]);
    for (std::size_t m = 0; m < 6; ++m) {
      BC[b][m] =
          name(fmt::format("dBCa{}_{}", m, body), fmt::format("dBCb{}_{}", m, body), BC[b][m]);
    }
    if (bodies[b].parent < 0) continue;
    const auto p = static_cast<std::size_t>(bodies[b].parent);
    IC[p].m += IC[b].m;
    IC[p].h = plus(IC[p].h, IC[b].h);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) IC[p].I[i][j] += IC[b].I[i][j];
    FC[p] = plus(FC[p], FC[b]);
    GC[p] = plus(GC[p], GC[b]);
    HC[p] = plus(HC[p], HC[b]);
    for (std::size_t m = 0; m < 6; ++m) BC[p][m] = plus(BC[p][m], BC[b][m]);
  }
  // per joint i: I^C S_i, B^Cᵀ S_i (for the pairs j ⪯ i) and the two vectors the joints above
  // it pair with (i ≺ j)
  out.d.assign(n * 2 * n, 0);
  out.M.assign(n * n, 0);
  out.tau_rest.assign(n, 0);
  auto d_q = [&](std::size_t i, std::size_t j) -> ex& { return out.d[i * 2 * n + j]; };
  auto d_qd = [&](std::size_t i, std::size_t j) -> ex& { return out.d[i * 2 * n + n + j]; };
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (std::size_t jb = path[b].size() - K[b].S.size(); jb < path[b].size(); ++jb) {
      const Joint& Ji = joints[path[b][jb]];
      const std::string coord = column_name(s, Ji.coordinate);
      const Spatial X = name("dXa_" + coord, "dXb_" + coord, apply(IC[b], Ji.S));
      std::array<ex, 6> Y = transposed_apply(BC[b], Ji.S);
      for (int m = 0; m < 6; ++m)
        Y[static_cast<std::size_t>(m)] =
            name(fmt::format("dY{}_{}", m, coord), Y[static_cast<std::size_t>(m)]);
      // the whole force F^C = FC + GC: q̈ enters only here and in the pairs through it; a
      // ball's column pairs with its ball's earlier ones without the turning of S_i
      const Spatial turning = cross_force(Ji.S, plus(FC[b], GC[b]));
      const Spatial Zq_rest = plus(apply(IC[b], Ji.ddS), apply_columns(BC[b], Ji.dS));
      const Spatial Zq = name("dZqa_" + coord, "dZqb_" + coord, plus(turning, Zq_rest));
      const Spatial Zq_ball = Ji.ball ? name("dZra_" + coord, "dZrb_" + coord, Zq_rest) : Spatial{};
      // B = P + Pᵀ + h×̄ with P = (v×*) I and h×̄ x = x ×* h skew, so B S = Bᵀ S + 2 S ×* h
      Spatial BS{{Y[0], Y[1], Y[2]}, {Y[3], Y[4], Y[5]}};
      BS = plus(BS, scaled(cross_force(Ji.S, HC[b]), 2));
      const Spatial Zv = name("dZva_" + coord, "dZvb_" + coord,
                              plus(BS, Ji.ball ? apply(IC[b], Ji.chi) : scaled(apply(IC[b], Ji.dS), 2)));
      const std::size_t i = Ji.coordinate;
      out.tau_rest[i] = power(Ji.S, FC[b]).expand();
      for (std::size_t k = 0; k <= jb; ++k) {
        const Joint& Jj = joints[path[b][k]];
        const std::size_t j = Jj.coordinate;
        // composite rigid bodies: M_ji = S_j · I^C S_i for j ⪯ i
        out.M[i * n + j] = out.M[j * n + i] = power(Jj.S, X).expand();
        d_q(i, j) = (power(Jj.ddS, X) + dot6(Y, Jj.dS)).expand();
        d_qd(i, j) = (dot6(Y, Jj.S) + (Jj.ball ? power(Jj.chi, X) : 2 * power(Jj.dS, X))).expand();
        if (k == jb) continue;
        const bool one_ball = Ji.ball && Jj.ball == Ji.ball;
        d_q(j, i) = power(Jj.S, one_ball ? Zq_ball : Zq).expand();
        d_qd(j, i) = power(Jj.S, Zv).expand();
      }
    }
  }
  return out;
}

}  // namespace rigid::lagrange::detail
