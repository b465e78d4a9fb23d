// The 3D view (three.js): every body as its shape at each frame's pose, with toggles for the
// body frames, ω, L and the inertia ellipsoids; for a single free body, the Poinsot
// construction beside it. Renders only when the time, a toggle, the camera or the size changes.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { decodeArray } from './data.js';
import { el, saveDataUrl } from './format.js';
import { bodyRadius, equivalentBox, equivalentEllipsoid, principalRotation, shapeGeometry } from './shapes.js';
import { buildLinks } from './links.js';
import { buildPoinsot } from './poinsot.js';
import { buildRecorder } from './record.js';

const kBodyColours = [0x4e79a7, 0xf28e2b, 0x59a14f, 0xe15759, 0x76b7b2, 0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f, 0xbab0ac];

function arrow(colour) {
  const a = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, colour);
  a.visible = false;
  // drawn over the bodies: an arrow starts at the COM, inside its body
  a.line.material.depthTest = false;
  a.cone.material.depthTest = false;
  a.renderOrder = 10;
  a.line.renderOrder = 10;
  a.cone.renderOrder = 10;
  return a;
}

function maxNorm(v) {
  let m = 0;
  for (let i = 0; i < v.length; i += 3) m = Math.max(m, Math.hypot(v[i], v[i + 1], v[i + 2]));
  return m;
}

// L is constant in the world (a torque-free body, not a top about its pivot): every frame
// within 1e-5 |L(0)| of the first, far above float32's 6e-8 and far below any torque's effect
function constant(L) {
  const n0 = Math.hypot(L[0], L[1], L[2]);
  if (!(n0 > 0)) return false;
  for (let i = 3; i < L.length; i += 3) {
    if (Math.hypot(L[i] - L[0], L[i + 1] - L[1], L[i + 2] - L[2]) > 1e-5 * n0) return false;
  }
  return true;
}

export function buildView(report, player, root) {
  const section = el('section', { class: 'view' });
  const canvasBox = el('div', { class: 'canvas-box' });
  const toggles = el('div', { class: 'toggles' });
  section.append(canvasBox, toggles);
  root.append(section);

  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0xf7f7f7);
  canvasBox.append(renderer.domElement);

  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(3, -2, 5);
  scene.add(sun);

  const frames = report.frames;
  const n = frames.count;
  const meshCache = new Map();
  const bodies = (report.bodies ?? []).map((b, i) => {
    const f = frames.bodies[i];
    return {
      info: b,
      position: decodeArray(f.position),
      quaternion: decodeArray(f.quaternion),
      omega: decodeArray(f.omega),
      L: decodeArray(f.L),
      colour: kBodyColours[i % kBodyColours.length],
    };
  });

  // extent of the motion, for the point-mass markers, the grid and the camera
  const box = new THREE.Box3();
  for (const b of bodies) for (let k = 0; k < b.position.length; k += 3) box.expandByPoint(new THREE.Vector3(b.position[k], b.position[k + 1], b.position[k + 2]));
  for (const b of bodies) {
    b.geometry = shapeGeometry(b.info, report.meshes, meshCache);
    b.radius = bodyRadius(b.geometry, b.info);
  }
  const maxRadius = Math.max(1e-9, ...bodies.map((b) => b.radius));
  const motion = box.isEmpty() ? 0 : box.getSize(new THREE.Vector3()).length();
  const extent = Math.max(motion, 2 * maxRadius, 1e-6);

  const layers = { frames: [], omega: [], L: [], ellipsoids: [], paths: [] };
  for (const b of bodies) {
    // the group is at the COM, turned by R_WB; the shape sits at −com in it (body frame origin)
    const group = new THREE.Group();
    const inBody = new THREE.Group();
    inBody.position.set(-b.info.com[0], -b.info.com[1], -b.info.com[2]);
    group.add(inBody);
    const material = new THREE.MeshStandardMaterial({ color: b.colour, roughness: 0.6, metalness: 0.05 });
    const equivalent = equivalentEllipsoid(b.info);
    if (b.geometry) {
      inBody.add(new THREE.Mesh(b.geometry, material));
    } else if (b.info.free && Math.max(...equivalent) > 0) {
      // a free body of no known shape: the uniform box of the same mass and principal moments
      // (its long side along the axis of least inertia), so that a turn of any axis shows;
      // flat ones given a thickness to be seen, one side darker so that a flip shows too
      const sides = equivalentBox(b.info);
      const thin = Math.max(...sides) / 40;
      const faces = [0, 1, 2, 3, 4, 5].map((f) => (f === 1 || f === 3 || f === 5
        ? new THREE.MeshStandardMaterial({ color: new THREE.Color(b.colour).multiplyScalar(0.55), roughness: 0.6, metalness: 0.05 })
        : material));
      const e = new THREE.Mesh(new THREE.BoxGeometry(...sides.map((x) => Math.max(x, thin))), faces);
      e.quaternion.copy(principalRotation(b.info));
      group.add(e);
      b.radius = 0.5 * Math.hypot(...sides);
    } else if (Math.max(...equivalent) > 0) {
      // no shape of its own: the uniform ellipsoid of the same inertia, flat ones given a thickness to be seen
      const thin = Math.max(...equivalent) / 40;
      const e = new THREE.Mesh(new THREE.SphereGeometry(1, 48, 24), material);
      e.scale.set(...equivalent.map((x) => Math.max(x, thin)));
      e.quaternion.copy(principalRotation(b.info));
      group.add(e);
    } else {
      // a point mass
      b.radius = 0.045 * extent;
      group.add(new THREE.Mesh(new THREE.SphereGeometry(b.radius, 24, 12), material));
    }
    const axes = new THREE.AxesHelper(1.4 * b.radius);
    axes.visible = false;
    inBody.add(axes);
    layers.frames.push(axes);
    if (Math.max(...equivalent) > 0) {
      const e = new THREE.Mesh(new THREE.SphereGeometry(1, 32, 16),
        new THREE.MeshBasicMaterial({ color: 0x333333, wireframe: true, transparent: true, opacity: 0.35 }));
      const thin = Math.max(...equivalent) / 40;
      e.scale.set(...equivalent.map((x) => Math.max(x, thin)));
      e.quaternion.copy(principalRotation(b.info));
      e.visible = false;
      group.add(e);
      layers.ellipsoids.push(e);
    }
    scene.add(group);
    b.group = group;
    // the path of the COM, traced up to the current frame (only for a body that moves)
    const moves = box.isEmpty() ? false : (() => {
      const p = b.position;
      for (let k = 3; k < p.length; k += 3) if (p[k] !== p[0] || p[k + 1] !== p[1] || p[k + 2] !== p[2]) return true;
      return false;
    })();
    if (moves) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(b.position instanceof Float32Array ? b.position : Float32Array.from(b.position), 3));
      g.setDrawRange(0, 1);
      b.path = new THREE.Line(g, new THREE.LineBasicMaterial({ color: b.colour, transparent: true, opacity: 0.6 }));
      scene.add(b.path);
      layers.paths.push(b.path);
    }
    if (b.omega) {
      b.omegaArrow = arrow(0xd62728);
      b.omegaScale = (1.5 * b.radius) / Math.max(maxNorm(b.omega), 1e-300);
      scene.add(b.omegaArrow);
      layers.omega.push(b.omegaArrow);
    }
    if (b.L) {
      b.LArrow = arrow(0x2ca02c);
      b.LScale = (1.8 * b.radius) / Math.max(maxNorm(b.L), 1e-300);
      scene.add(b.LArrow);
      layers.L.push(b.LArrow);
    }
  }

  // rods and pivots (the report's links)
  const links = buildLinks(report.links, bodies, extent);
  scene.add(links.group);
  for (const p of links.pivots) box.expandByPoint(new THREE.Vector3(...p));

  const grid = new THREE.GridHelper(2 * extent, 20, 0xbbbbbb, 0xdddddd);
  grid.rotateX(Math.PI / 2);
  const centre = box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
  grid.position.set(centre.x, centre.y, (box.isEmpty() ? 0 : box.min.z) - maxRadius);
  scene.add(grid);

  // the Poinsot construction, for a single free body with ω and L
  let poinsot = null;
  if (bodies.length === 1 && bodies[0].info.free && bodies[0].omega && bodies[0].L && constant(bodies[0].L)) {
    poinsot = buildPoinsot(bodies[0], n);
    scene.add(poinsot.group);
  }

  const camera = new THREE.PerspectiveCamera(40, 1, extent / 1000, extent * 100);
  camera.up.set(0, 0, 1);
  // what the camera frames: the motion's box grown by the largest body, and the Poinsot
  // construction beside it
  const frame = box.isEmpty() ? new THREE.Box3(centre.clone(), centre.clone()) : box.clone();
  // (point masses got their marker's radius above), and by the ω and L arrows (≤ 1.8 radii)
  const arrows = bodies.some((b) => b.omega || b.L) ? 1.8 : 1;
  frame.expandByScalar(arrows * Math.max(maxRadius, ...bodies.map((b) => b.radius)));
  if (poinsot) {
    const c = centre.clone().add(poinsot.offset);
    frame.union(new THREE.Box3().setFromCenterAndSize(c, new THREE.Vector3(1, 1, 1).multiplyScalar(3.2 * maxRadius)));
  }
  const target = frame.getCenter(new THREE.Vector3());
  const span = frame.getSize(new THREE.Vector3());
  const kView = new THREE.Vector3(0.15, -1.6, 0.6).normalize();
  let cameraMoved = false;
  // the camera looks along about +y: x spans the width, z the height, y the depth; the
  // distance fits both in the view with a 10 % margin
  const placeCamera = () => {
    const tanV = Math.tan(THREE.MathUtils.degToRad(camera.fov / 2));
    const tanH = tanV * camera.aspect;
    const dist = 1.1 * (Math.max(span.z / 2 / tanV, span.x / 2 / tanH) + span.y / 2);
    camera.position.copy(target).addScaledVector(kView, Math.max(dist, 1e-6));
  };
  placeCamera();
  // a light from the camera, so no face the user looks at is left dark
  const headlight = new THREE.DirectionalLight(0xffffff, 0.9);
  camera.add(headlight);
  scene.add(camera);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(target);
  controls.update();

  let pending = false;
  const render = () => {
    pending = false;
    renderer.render(scene, camera);
  };
  const requestRender = () => {
    if (!pending) { pending = true; requestAnimationFrame(render); }
  };
  controls.addEventListener('change', requestRender);
  controls.addEventListener('start', () => { cameraMoved = true; });

  const q = new THREE.Quaternion();
  const v = new THREE.Vector3();
  const setFrame = (k) => {
    for (const b of bodies) {
      const p = b.position;
      if (b.path) b.path.geometry.setDrawRange(0, k + 1);
      b.group.position.set(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
      const w = b.quaternion;
      b.group.quaternion.set(w[4 * k + 1], w[4 * k + 2], w[4 * k + 3], w[4 * k]);
      for (const [arr, data, scale] of [[b.omegaArrow, b.omega, b.omegaScale], [b.LArrow, b.L, b.LScale]]) {
        if (!arr) continue;
        v.set(data[3 * k], data[3 * k + 1], data[3 * k + 2]);
        const len = v.length() * scale;
        arr.position.copy(b.group.position);
        if (len > 0) {
          arr.setDirection(v.normalize());
          arr.setLength(len, Math.min(0.25 * len, 0.3 * b.radius), Math.min(0.12 * len, 0.15 * b.radius));
        }
      }
    }
    links.setFrame(k);
    if (poinsot) poinsot.setFrame(k, bodies[0].group.position, q.copy(bodies[0].group.quaternion));
    requestRender();
  };

  const resize = () => {
    const w = Math.max(320, canvasBox.clientWidth);
    const h = Math.round(Math.min(560, Math.max(320, w * 0.55)));
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    if (!cameraMoved) {
      placeCamera();
      controls.update();
    }
    requestRender();
  };
  window.addEventListener('resize', resize);

  // toggles
  const toggle = (label, items, on, note) => {
    if (!items.length) return;
    const box = el('input', { type: 'checkbox' });
    box.checked = on;
    const apply = () => {
      for (const it of items) it.visible = box.checked;
      requestRender();
    };
    box.addEventListener('change', apply);
    apply();
    toggles.append(el('label', { title: note ?? '' }, box, ` ${label}`));
  };
  // a free body's turning is read from its frame: on by default where there is one
  toggle('body frames', layers.frames, bodies.some((b) => b.info.free), 'x red, y green, z blue, at each body frame origin');
  toggle('rods and pivots', links.count ? [links.group] : [], true, 'what connects the bodies: a rod to what a body hangs from, a sphere at a pivot fixed in the world, the springs, the constraints\' ropes');
  toggle('ω', layers.omega, true, 'angular velocity in the world (red)');
  toggle('L', layers.L, true, 'angular momentum about the COM, in the world (green): constant for a free body');
  toggle('inertia ellipsoids', layers.ellipsoids, false, 'the uniform solid ellipsoid with the body’s mass and principal moments');
  if (poinsot) toggle('Poinsot construction', [poinsot.group], true, poinsot.note);
  toggle('paths', layers.paths, true, 'the path of each body’s COM up to the current time');
  toggle('grid', [grid], true);

  const download = el('button', { type: 'button', class: 'download', title: 'the 3D view as it is now, as a PNG image', text: 'PNG' });
  download.addEventListener('click', () => {
    render();
    saveDataUrl(renderer.domElement.toDataURL('image/png'), `${report.scene?.name ?? 'rigid'}-view.png`);
  });
  toggles.append(download);
  // the animation as a video (or PNG frames), beside the player
  const fileName = String(report.scene?.name ?? 'rigid').replace(/[^\w.-]+/g, '_');
  const recorder = player.bar ? buildRecorder({ canvas: renderer.domElement, render, player, name: fileName, bar: player.bar }) : null;

  resize();
  player.onChange(setFrame);
  setFrame(player.index);
  render();
  const project = (p) => {
    const v3 = new THREE.Vector3(...p).project(camera);
    const r = renderer.domElement.getBoundingClientRect();
    return [(v3.x + 1) / 2 * r.width, (1 - v3.y) / 2 * r.height];
  };
  return {
    renderer,
    render,
    recorder,
    canvas: renderer.domElement,
    // for tests and scripts: the rods' world ends at the current frame, the pivots, a world
    // point's position in the canvas (CSS pixels), a body's drawn orientation (w, x, y, z)
    links: () => links.ends(player.index),
    linkRules: links.rules,
    linkRadii: links.radii,
    pivots: links.pivots,
    project,
    bodyQuaternion: (i) => { const g = bodies[i].group.quaternion; return [g.w, g.x, g.y, g.z]; },
  };
}
