// What connects the bodies (the report's `links`): a rod from a point of a body to a point of
// the body it hangs from, or to a pivot fixed in the world (drawn as a sphere); a small sphere
// where a rod meets a body. Rods are cylinders of one unit length, stretched and turned each frame.
import * as THREE from 'three';

const kRodColour = 0x3b3b3b;
const kPivotColour = 0x111111;

/** The world position of the body-frame point `p` of body `b` at frame k (b.position is the COM). */
export function worldPoint(b, p, k, out = new THREE.Vector3()) {
  const w = b.quaternion;
  const q = new THREE.Quaternion(w[4 * k + 1], w[4 * k + 2], w[4 * k + 3], w[4 * k]).normalize();
  out.set(p[0] - b.info.com[0], p[1] - b.info.com[1], p[2] - b.info.com[2]).applyQuaternion(q);
  return out.add(new THREE.Vector3(b.position[3 * k], b.position[3 * k + 1], b.position[3 * k + 2]));
}

/**
 * Builds the rods and pivots of `links` for `bodies` (view3d's, with position, quaternion and
 * info); `extent` (m) sizes them. Returns {group, pivots, setFrame(k), ends(k)}: ends gives each
 * rod's two world points [body end, other end] at frame k.
 */
export function buildLinks(links, bodies, extent) {
  const group = new THREE.Group();
  const valid = (links ?? []).filter((l) => bodies[l.body] && (l.to === null || bodies[l.to]));
  const rodRadius = 0.008 * extent;
  const rodMaterial = new THREE.MeshStandardMaterial({ color: kRodColour, roughness: 0.5 });
  const pivotMaterial = new THREE.MeshStandardMaterial({ color: kPivotColour, roughness: 0.4 });
  const unitRod = new THREE.CylinderGeometry(1, 1, 1, 12).translate(0, 0.5, 0);
  const ball = new THREE.SphereGeometry(1, 20, 10);
  const pivots = [];
  const rods = valid.map((l) => {
    const rod = new THREE.Mesh(unitRod, rodMaterial);
    group.add(rod);
    const joint = new THREE.Mesh(ball, rodMaterial);
    joint.scale.setScalar(1.8 * rodRadius);
    group.add(joint);
    if (l.to === null) {
      const pivot = new THREE.Mesh(ball, pivotMaterial);
      pivot.scale.setScalar(0.025 * extent);
      pivot.position.set(...l.to_point);
      group.add(pivot);
      pivots.push(l.to_point);
    }
    return { link: l, rod, joint };
  });
  const a = new THREE.Vector3();
  const b = new THREE.Vector3();
  const up = new THREE.Vector3(0, 1, 0);
  const ends = (k) => valid.map((l) => {
    const from = worldPoint(bodies[l.body], l.point, k);
    const to = l.to === null ? new THREE.Vector3(...l.to_point) : worldPoint(bodies[l.to], l.to_point, k);
    return [from.toArray(), to.toArray()];
  });
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
      r.rod.scale.set(rodRadius, len, rodRadius);
    }
  };
  return { group, pivots, count: rods.length, setFrame, ends };
}
