// The Poinsot construction of a free body, drawn beside it: the energy ellipsoid
// {x : xᵀ I x = 2E} turns with the body and rolls without slipping on the invariable plane
// {x : x · L = 2E}, touching it at ω. The polhode (the path of ω on the ellipsoid, in the body)
// and the herpolhode (its path on the plane, in the world) are traced up to the current frame.
// Everything is scaled by one factor s so it is as large as the body; the touching holds at any s.
import * as THREE from 'three';
import { principalRotation } from './shapes.js';

function line(points, colour) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(points, 3));
  g.setDrawRange(0, 1);
  return new THREE.Line(g, new THREE.LineBasicMaterial({ color: colour }));
}

export function buildPoinsot(body, n) {
  const info = body.info;
  const w = body.omega;
  const q = body.quaternion;
  const Lw = new THREE.Vector3(body.L[0], body.L[1], body.L[2]);
  const Lnorm = Lw.length();

  // ω in the body frame, ω_B = R_WBᵀ ω_W, for the polhode; the kinetic energy from frame 0
  const omegaB = new Float32Array(3 * n);
  const rot = new THREE.Quaternion();
  const v = new THREE.Vector3();
  for (let k = 0; k < n; k += 1) {
    rot.set(q[4 * k + 1], q[4 * k + 2], q[4 * k + 3], q[4 * k]).invert();
    v.set(w[3 * k], w[3 * k + 1], w[3 * k + 2]).applyQuaternion(rot);
    omegaB.set([v.x, v.y, v.z], 3 * k);
  }
  const axes = info.principal_axes;
  const I = info.principal_moments;
  let twoE = 0;
  for (let i = 0; i < 3; i += 1) {
    const wi = omegaB[0] * axes[i][0] + omegaB[1] * axes[i][1] + omegaB[2] * axes[i][2];
    twoE += I[i] * wi * wi;
  }
  const semi = I.map((Ii) => Math.sqrt(twoE / Ii));
  const s = (0.9 * body.radius) / Math.max(...semi);

  const group = new THREE.Group();
  // beside the body along world x (its part ⟂ L, so the plane does not cross the body), to
  // the right of the front camera
  const Lhat = Lw.clone().normalize();
  let across = new THREE.Vector3(1, 0, 0).addScaledVector(Lhat, -Lhat.x);
  if (across.length() < 0.3) across = new THREE.Vector3(0, 1, 0).addScaledVector(Lhat, -Lhat.y);
  const offset = across.normalize().multiplyScalar(2.6 * body.radius);

  const turning = new THREE.Group();
  const ellipsoid = new THREE.Mesh(new THREE.SphereGeometry(1, 48, 24),
    new THREE.MeshStandardMaterial({ color: 0xf0c05a, roughness: 0.5, transparent: true, opacity: 0.75 }));
  ellipsoid.scale.set(s * semi[0], s * semi[1], s * semi[2]);
  ellipsoid.quaternion.copy(principalRotation(info));
  turning.add(ellipsoid);
  const polhode = line(omegaB.map((x) => s * x), 0x7a1fa2);
  turning.add(polhode);
  group.add(turning);

  const d = (s * twoE) / Lnorm;
  const planeSize = 3.2 * s * Math.max(...semi);
  const plane = new THREE.Mesh(new THREE.PlaneGeometry(planeSize, planeSize),
    new THREE.MeshBasicMaterial({ color: 0x8fb3d9, transparent: true, opacity: 0.35, side: THREE.DoubleSide, depthWrite: false }));
  plane.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), Lhat);
  plane.position.copy(Lhat).multiplyScalar(d);
  group.add(plane);
  const herpolhode = line(Float32Array.from(w, (x) => s * x), 0x1f4fa2);
  group.add(herpolhode);
  const contact = new THREE.Mesh(new THREE.SphereGeometry(0.03 * s * Math.max(...semi), 12, 8),
    new THREE.MeshBasicMaterial({ color: 0xd62728 }));
  group.add(contact);

  return {
    group,
    offset,
    note: `energy ellipsoid (semi-axes √(2E/Iᵢ)) rolling on the invariable plane ⟂ L at 2E/|L|; polhode (purple), herpolhode (blue); drawn ×${s.toPrecision(3)}`,
    setFrame(k, comW, R_WB) {
      group.position.copy(comW).add(offset);
      turning.quaternion.copy(R_WB);
      polhode.geometry.setDrawRange(0, k + 1);
      herpolhode.geometry.setDrawRange(0, k + 1);
      contact.position.set(s * w[3 * k], s * w[3 * k + 1], s * w[3 * k + 2]);
    },
  };
}
