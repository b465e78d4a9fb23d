// Geometry of each body's shape in its body frame, after the primitive catalogue's frames
// (docs/mass.md): centred primitives with their axis along z, the cone and the frustum with
// their base at z = 0; meshes from the report's `meshes[]`, each built once and shared.
import * as THREE from 'three';
import { decodeArray } from './data.js';

const kAliases = {
  sphere: 'sphere', solid_sphere: 'sphere', thin_spherical_shell: 'sphere', hollow_sphere: 'sphere',
  thick_spherical_shell: 'sphere', spherical_shell: 'sphere',
  ellipsoid: 'ellipsoid', solid_ellipsoid: 'ellipsoid',
  box: 'box', solid_box: 'box', cuboid: 'box',
  cylinder: 'cylinder', solid_cylinder: 'cylinder', thin_cylindrical_shell: 'cylinder', cylindrical_shell: 'cylinder',
  capped_cylindrical_shell: 'cylinder', closed_cylindrical_shell: 'cylinder',
  tube: 'cylinder', thick_tube: 'cylinder', thick_walled_tube: 'cylinder',
  cone: 'cone', solid_cone: 'cone', frustum: 'frustum', solid_frustum: 'frustum',
  capsule: 'capsule', solid_capsule: 'capsule', torus: 'torus', solid_torus: 'torus',
  rod: 'rod', thin_rod: 'rod', plate: 'plate', thin_rectangular_plate: 'plate', rectangular_plate: 'plate',
  disk: 'disk', disc: 'disk', thin_disk: 'disk', mesh: 'mesh',
};

/** Semi-axes of the uniform solid ellipsoid with the body's principal moments and mass:
 *  I1 = m (b² + c²) / 5 and cyclically, so a² = 5 (I2 + I3 − I1) / (2m). */
export function equivalentEllipsoid(body) {
  const [i1, i2, i3] = body.principal_moments;
  const m = body.mass > 0 ? body.mass : 1;
  const k = 5 / (2 * m);
  return [k * (i2 + i3 - i1), k * (i1 + i3 - i2), k * (i1 + i2 - i3)].map((x) => Math.sqrt(Math.max(0, x)));
}

/** Sides of the uniform solid box with the body's principal moments and mass:
 *  I1 = m (b² + c²) / 12 and cyclically, so a² = 6 (I2 + I3 − I1) / m. */
export function equivalentBox(body) {
  const [i1, i2, i3] = body.principal_moments;
  const m = body.mass > 0 ? body.mass : 1;
  const k = 6 / m;
  return [k * (i2 + i3 - i1), k * (i1 + i3 - i2), k * (i1 + i2 - i3)].map((x) => Math.sqrt(Math.max(0, x)));
}

/** Rotation (three.js) whose columns are the body's principal axes. */
export function principalRotation(body) {
  const [a0, a1, a2] = body.principal_axes;
  const m = new THREE.Matrix4().set(
    a0[0], a1[0], a2[0], 0,
    a0[1], a1[1], a2[1], 0,
    a0[2], a1[2], a2[2], 0,
    0, 0, 0, 1);
  return new THREE.Quaternion().setFromRotationMatrix(m);
}

function size(sizes, ...names) {
  for (const n of names) if (typeof sizes[n] === 'number') return sizes[n];
  return undefined;
}

const kSegments = 40;

function alongZ(g) { return g.rotateX(Math.PI / 2); }

function meshGeometry(mesh) {
  const pos = decodeArray(mesh.positions);
  const idx = decodeArray(mesh.indices);
  let positions = pos instanceof Float32Array ? pos : Float32Array.from(pos);
  if (mesh.quantised && mesh.scale && mesh.offset) {
    // quantised positions: p = offset + q · scale, per axis
    positions = Float32Array.from(pos, (q, i) => mesh.offset[i % 3] + q * mesh.scale[i % 3]);
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  if (idx) g.setIndex(new THREE.BufferAttribute(idx instanceof Uint32Array ? idx : Uint32Array.from(idx), 1));
  g.computeVertexNormals();
  return g;
}

/**
 * The body's geometry in its body frame, or null when it has no shape of its own (inertia only,
 * point masses): the caller then draws its equivalent ellipsoid or a marker.
 * `meshCache` maps a mesh index to its geometry, built once.
 */
export function shapeGeometry(body, meshes, meshCache) {
  const shape = body.shape ?? {};
  const canonical = (name) => kAliases[String(name ?? '').replace(/-/g, '_')];
  // a primitive the writer did not map onto a kind of its own (inertia_only) is still drawn
  const kind = canonical(shape.kind) ?? canonical(shape.primitive);
  const s = shape.sizes ?? {};
  const r = size(s, 'radius', 'outer_radius', 'bottom_radius');
  const h = size(s, 'height', 'length');
  let g = null;
  switch (kind) {
    case 'sphere': if (r) g = new THREE.SphereGeometry(r, kSegments, kSegments / 2); break;
    case 'ellipsoid': {
      const a = [size(s, 'semi_x', 'semi_axes_0', 'a', 'x'), size(s, 'semi_y', 'semi_axes_1', 'b', 'y'), size(s, 'semi_z', 'semi_axes_2', 'c', 'z')];
      if (a.every((x) => x > 0)) g = new THREE.SphereGeometry(1, kSegments, kSegments / 2).scale(a[0], a[1], a[2]);
      break;
    }
    case 'box': {
      const l = [size(s, 'lx', 'size_0', 'x'), size(s, 'ly', 'size_1', 'y'), size(s, 'lz', 'size_2', 'z')];
      if (l.every((x) => x > 0)) g = new THREE.BoxGeometry(l[0], l[1], l[2]);
      break;
    }
    case 'cylinder': if (r && h) g = alongZ(new THREE.CylinderGeometry(r, r, h, kSegments)); break;
    case 'cone': if (r && h) g = alongZ(new THREE.CylinderGeometry(0, r, h, kSegments)).translate(0, 0, h / 2); break;
    case 'frustum': {
      const top = size(s, 'top_radius');
      if (r && h && top !== undefined) g = alongZ(new THREE.CylinderGeometry(top, r, h, kSegments)).translate(0, 0, h / 2);
      break;
    }
    case 'capsule': {
      const len = size(s, 'length', 'height');
      if (r && len !== undefined) g = alongZ(new THREE.CapsuleGeometry(r, len, 8, kSegments));
      break;
    }
    case 'torus': {
      const R = size(s, 'major_radius');
      const rr = size(s, 'minor_radius');
      if (R && rr) g = new THREE.TorusGeometry(R, rr, kSegments / 2, kSegments);
      break;
    }
    case 'rod': if (h) g = alongZ(new THREE.CylinderGeometry(h / 80, h / 80, h, 12)); break;
    case 'plate': {
      const lx = size(s, 'lx', 'size_0');
      const ly = size(s, 'ly', 'size_1');
      if (lx && ly) g = new THREE.BoxGeometry(lx, ly, Math.min(lx, ly) / 60);
      break;
    }
    case 'disk': if (r) g = alongZ(new THREE.CylinderGeometry(r, r, r / 30, kSegments)); break;
    case 'mesh': {
      const i = shape.mesh;
      if (meshes && meshes[i]) {
        if (!meshCache.has(i)) meshCache.set(i, meshGeometry(meshes[i]));
        g = meshCache.get(i);
      }
      break;
    }
    default: break;
  }
  return g;
}

/** Radius of a sphere about the COM that holds the body's drawing (m), for scales. */
export function bodyRadius(geometry, body) {
  if (geometry) {
    if (!geometry.boundingSphere) geometry.computeBoundingSphere();
    const c = new THREE.Vector3(...body.com);
    const bs = geometry.boundingSphere;
    return bs.radius + bs.center.distanceTo(c);
  }
  return Math.max(...equivalentEllipsoid(body));
}
