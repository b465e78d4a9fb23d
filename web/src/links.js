// What connects the bodies (the report's `links`): a rod from a point of a body to a point of
// the body it hangs from, or to a pivot fixed in the world (drawn as a sphere); a small sphere
// where a rod meets a body. A spring (rule "spring") is a coil and a constraint's rope (rule
// "rope") a thin cord between its two points, a spring's world anchor a small sphere. Each is
// made once and stretched and turned each frame (a coil stretches as a spring does).
import * as THREE from 'three';

const kRodColour = 0x3b3b3b;
const kPivotColour = 0x111111;
const kRopeColour = 0x4a3a28;
const kSpringColour = 0x23344f;
const kSpringTurns = 10;

// A coil of kSpringTurns turns of radius `radius` along y from 0 to `length` (m), as a tube a
// fifth of the coil's radius thick: the spring at `length`, which scaling along y stretches.
function coil(radius, length) {
  class Helix extends THREE.Curve {
    getPoint(u, out = new THREE.Vector3()) {
      const a = 2 * Math.PI * kSpringTurns * u;
      return out.set(radius * Math.cos(a), length * u, radius * Math.sin(a));
    }
  }
  return new THREE.TubeGeometry(new Helix(), 24 * kSpringTurns, 0.2 * radius, 6, false);
}

/** The world position of the body-frame point `p` of body `b` at frame k (b.position is the COM). */
export function worldPoint(b, p, k, out = new THREE.Vector3()) {
  const w = b.quaternion;
  const q = new THREE.Quaternion(w[4 * k + 1], w[4 * k + 2], w[4 * k + 3], w[4 * k]).normalize();
  out.set(p[0] - b.info.com[0], p[1] - b.info.com[1], p[2] - b.info.com[2]).applyQuaternion(q);
  return out.add(new THREE.Vector3(b.position[3 * k], b.position[3 * k + 1], b.position[3 * k + 2]));
}

/**
 * Builds the rods and pivots of `links` for `bodies` (view3d's, with position, quaternion and
 * info); `extent` (m) sizes them. Returns {group, pivots, setFrame(k), ends(k), rules,
 * radii}: ends gives each link's two world points [body end, other end] at frame k, rules its
 * rule, radii the radius it is drawn with (m; a spring's coil).
 */
export function buildLinks(links, bodies, extent) {
  const group = new THREE.Group();
  const valid = (links ?? []).filter((l) => bodies[l.body] && (l.to === null || bodies[l.to]));
  const rodRadius = 0.008 * extent;
  const ball = new THREE.SphereGeometry(1, 20, 10);
  const unitRod = new THREE.CylinderGeometry(1, 1, 1, 12).translate(0, 0.5, 0);
  const material = (color) => new THREE.MeshStandardMaterial({ color, roughness: 0.5 });
  // per rule (a rod's rule says how it was found: "parent", "pivot", …): the unit shape, its
  // radius (m), its material
  const styles = {
    rod: { shape: unitRod, radius: rodRadius, material: material(kRodColour) },
    rope: { shape: unitRod, radius: 0.4 * rodRadius, material: material(kRopeColour) },
    spring: { radius: 0.03 * extent, material: material(kSpringColour) },
  };
  const ends = (k) => valid.map((l) => {
    const from = worldPoint(bodies[l.body], l.point, k);
    const to = l.to === null ? new THREE.Vector3(...l.to_point) : worldPoint(bodies[l.to], l.to_point, k);
    return [from.toArray(), to.toArray()];
  });
  // a coil is made at its length in the first frame (a rod's shape is one unit long) and scaled
  // along its axis by its length over that
  const first = valid.length ? ends(0) : [];
  const firstLength = (i) => {
    const [p, q] = first[i];
    return Math.max(Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]), 1e-3 * extent);
  };
  const pivotMaterial = new THREE.MeshStandardMaterial({ color: kPivotColour, roughness: 0.4 });
  const pivots = [];
  const rods = valid.map((l, i) => {
    const style = styles[l.rule] ?? styles.rod;
    const length = style === styles.spring ? firstLength(i) : 1;
    const rod = new THREE.Mesh(style === styles.spring ? coil(style.radius, length) : style.shape, style.material);
    group.add(rod);
    const joint = new THREE.Mesh(ball, style.material);
    joint.scale.setScalar(1.8 * (style === styles.rod ? rodRadius : 0.5 * rodRadius));
    group.add(joint);
    if (l.to === null && l.rule !== 'rope') {
      // a pivot of a rod, a spring's anchor; a rope's end in the world is where it leaves a
      // pulley or a wall, drawn by what is there
      const pivot = new THREE.Mesh(ball, pivotMaterial);
      pivot.scale.setScalar((l.rule === 'spring' ? 0.012 : 0.025) * extent);
      pivot.position.set(...l.to_point);
      group.add(pivot);
      if (l.rule !== 'spring') pivots.push(l.to_point);
    }
    // the scale that draws it at length len: a rod's shape is unit, a coil keeps its radius
    const across = style === styles.spring ? 1 : style.radius;
    return { link: l, rod, joint, radius: style.radius, across, length };
  });
  const a = new THREE.Vector3();
  const b = new THREE.Vector3();
  const up = new THREE.Vector3(0, 1, 0);
  const setFrame = (k) => {
    for (const r of rods) {
      worldPoint(bodies[r.link.body], r.link.point, k, a);
      if (r.link.to === null) b.set(...r.link.to_point); else worldPoint(bodies[r.link.to], r.link.to_point, k, b);
      r.joint.position.copy(a);
      const d = b.clone().sub(a);
      const len = d.length();
      r.rod.visible = len > 1e-9 * extent;
      if (!r.rod.visible) continue;
      r.rod.position.copy(a);
      r.rod.quaternion.setFromUnitVectors(up, d.divideScalar(len));
      r.rod.scale.set(r.across, len / r.length, r.across);
    }
  };
  return { group, pivots, count: rods.length, setFrame, ends, rules: rods.map((r) => r.link.rule), radii: rods.map((r) => r.radius) };
}
