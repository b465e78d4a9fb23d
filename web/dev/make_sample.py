#!/usr/bin/python3
"""Builds a schema-v1 report page from a `rigid run` output directory, for developing the page
before (or apart from) the C++ side:

    web/dev/make_sample.py RUN_DIR SCENE.toml BUNDLE_DIR OUT.html [--max-frames N]

RUN_DIR holds trajectory.csv and summary.json; BUNDLE_DIR holds report.js and report.css
(`node web/build.mjs BUNDLE_DIR`). Bodies' inertias come from the scene's `inertia` tables or
point masses (other bodies are written as inertia_only with a unit inertia); rigid itself writes
the real data.
"""
import argparse
import base64
import csv
import json
import math
import sys
import tomllib

import numpy as np


def f32(a):
    a = np.asarray(a, dtype='<f4').ravel()
    if a.size <= 16:
        return [float(x) for x in a]
    return 'f32:' + base64.b64encode(a.tobytes()).decode()


def rotate(q, v):
    """v rotated by the unit quaternion q = (w, x, y, z), row by row."""
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    R = np.empty((len(q), 3, 3))
    R[:, 0, 0] = 1 - 2 * (y * y + z * z); R[:, 0, 1] = 2 * (x * y - w * z); R[:, 0, 2] = 2 * (x * z + w * y)
    R[:, 1, 0] = 2 * (x * y + w * z); R[:, 1, 1] = 1 - 2 * (x * x + z * z); R[:, 1, 2] = 2 * (y * z - w * x)
    R[:, 2, 0] = 2 * (x * z - w * y); R[:, 2, 1] = 2 * (y * z + w * x); R[:, 2, 2] = 1 - 2 * (x * x + y * y)
    return np.einsum('nij,nj->ni', R, v)


def value(v, params):
    if isinstance(v, (int, float)):
        return float(v)
    return float(eval(str(v), {'__builtins__': {}}, dict(params, sin=math.sin, cos=math.cos, pi=math.pi)))


def body_inertia(b, params):
    if 'inertia' in b:
        i = b['inertia']
        m = value(i.get('mass', 1), params)
        I = np.array([[value(i.get('ixx', 0), params), value(i.get('ixy', 0), params), value(i.get('ixz', 0), params)],
                      [0, value(i.get('iyy', 0), params), value(i.get('iyz', 0), params)],
                      [0, 0, value(i.get('izz', 0), params)]])
        I = np.triu(I) + np.triu(I, 1).T
        return m, np.zeros(3), I
    if 'point_masses' in b:
        ms = np.array([value(p['mass'], params) for p in b['point_masses']])
        ps = np.array([[value(c, params) for c in p.get('position', [0, 0, 0])] for p in b['point_masses']])
        m = ms.sum()
        c = (ms[:, None] * ps).sum(0) / m
        d = ps - c
        I = sum(mi * (di @ di * np.eye(3) - np.outer(di, di)) for mi, di in zip(ms, d))
        return m, c, I
    return 1.0, np.zeros(3), np.eye(3)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('run_dir'); ap.add_argument('scene'); ap.add_argument('bundle'); ap.add_argument('out')
    ap.add_argument('--max-frames', type=int, default=2000)
    a = ap.parse_args()
    summary = json.load(open(f'{a.run_dir}/summary.json'))
    with open(f'{a.run_dir}/trajectory.csv') as f:
        rows = list(csv.reader(f))
    cols = rows[0]
    data = np.array(rows[1:], dtype=float)
    col = {c: data[:, i] for i, c in enumerate(cols)}
    scene = tomllib.load(open(a.scene, 'rb'))
    params = {k: float(v) for k, v in summary.get('parameters', {}).items()}

    n_all = len(data)
    stride = max(1, math.ceil(n_all / a.max_frames))
    idx = np.arange(0, n_all, stride)
    rule = (f'every sample of {n_all}' if stride == 1 else
            f'every {stride}th of {n_all} samples (at most {a.max_frames} frames)')

    bodies, frames_bodies, series = [], [], []
    names = [b['name'] for b in scene.get('bodies', [])]
    for b in scene.get('bodies', []):
        n = b['name']
        m, c, I = body_inertia(b, params)
        w, V = np.linalg.eigh(I)
        if np.linalg.det(V) < 0:
            V[:, 2] = -V[:, 2]
        kind = 'inertia_only'
        sizes = {}
        if 'primitive' in b:
            kind = b['primitive']
            sizes = {k: value(v, params) for k, v in b.items()
                     if k in ('radius', 'height', 'lx', 'ly', 'lz', 'length', 'inner_radius', 'outer_radius')}
        bodies.append({'name': n, 'mass': m, 'com': c.tolist(), 'inertia_com': I.tolist(),
                       'principal_moments': w.tolist(), 'principal_axes': V.T.tolist(),
                       'shape': {'kind': kind, 'sizes': sizes}, 'free': bool(b.get('free', False))})
        q = np.stack([col[f'{n}.q{k}'] for k in 'wxyz'], 1)[idx]
        p = np.stack([col[f'{n}.{k}'] for k in 'xyz'], 1)[idx]
        p = p + rotate(q, np.tile(c, (len(q), 1)))  # body origin -> COM
        fb = {'position': f32(p), 'quaternion': f32(q), 'omega': None, 'L': None}
        if f'{n}.wx' in col:
            wb = np.stack([col[f'{n}.w{k}'] for k in 'xyz'], 1)[idx]
            fb['omega'] = f32(rotate(q, wb))
            fb['L'] = f32(np.stack([col[f'{n}.L{k}'] for k in 'xyz'], 1)[idx])
            Lx, Ly, Lz = (col[f'{n}.L{k}'] for k in 'xyz')
            Ln = np.sqrt(Lx * Lx + Ly * Ly + Lz * Lz)
            series.append({'group': 'L_error', 'name': f'{n} ||L| − |L(0)|| / |L(0)|', 'unit': '', 'column': f'{n}.L',
                           'values': f32(np.abs(Ln - Ln[0])[idx] / (Ln[0] if Ln[0] != 0 else 1.0))})
        frames_bodies.append(fb)

    units = {'x': 'm', 'y': 'm', 'z': 'm', 'vx': 'm/s', 'vy': 'm/s', 'vz': 'm/s',
             'wx': 'rad/s', 'wy': 'rad/s', 'wz': 'rad/s', 'Lx': 'kg·m²/s', 'Ly': 'kg·m²/s', 'Lz': 'kg·m²/s',
             'qw': '', 'qx': '', 'qy': '', 'qz': ''}
    coords = [c['name'] for c in scene.get('coordinates', [])]
    for c in cols[1:]:
        head, _, tail = c.partition('.')
        if c in coords:
            g, u = 'coordinates', ''
        elif c.endswith('_dot') and c[:-4] in coords:
            g, u = 'velocities', ''
        elif head in names and tail in units:
            if tail in ('x', 'y', 'z', 'qw', 'qx', 'qy', 'qz'):
                continue  # poses: in frames, not plotted (as rigid writes it)
            g = 'other' if tail[0] == 'L' else 'velocities'
            u = units[tail]
        elif c.startswith('lambda_') or c.startswith('mu_'):
            g, u = 'multipliers', ''
        elif 'residual' in c:
            g, u = 'residuals', ''
        elif c in ('energy', 'jacobi'):
            e = col[c]
            if c == 'energy':  # relative, or absolute when E(0) = 0 (as rigid writes it)
                scale = abs(e[0]) if e[0] != 0 else 1.0
                series.append({'group': 'energy_error', 'name': '|E − E(0)| / |E(0)|', 'unit': '', 'column': c,
                               'values': f32(np.abs(e - e[0])[idx] / scale)})
            g, u = 'other', 'J'
        else:
            g, u = 'other', ''
        series.append({'group': g, 'name': c, 'unit': u, 'column': c, 'values': f32(col[c][idx])})

    desc = []
    for line in open(a.scene):
        if not line.startswith('#'):
            break
        desc.append(line[1:].strip())
    report = {
        'rigid_report': 1,
        'scene': {'name': a.scene.rsplit('/', 1)[-1].removesuffix('.toml'), 'file': a.scene,
                  'description': '\n'.join(desc)},
        'kind': summary['kind'],
        'parameters': [{'name': k, 'value': v, 'unit': ''} for k, v in params.items()],
        'integrator': {'method': summary['integrator'], 'dt': summary.get('dt'),
                       'tolerance': summary.get('tolerance', 0), 'steps': summary.get('steps'),
                       'rhs_evaluations': summary.get('rhs_evaluations', 0),
                       'wall_time_s': summary.get('wall_time_s')},
        'diagnostics': summary.get('diagnostics', {}),
        'equations_latex': (r'\begin{aligned} I_1\dot\omega_1 &= (I_2 - I_3)\,\omega_2\omega_3 \\'
                            r' I_2\dot\omega_2 &= (I_3 - I_1)\,\omega_3\omega_1 \end{aligned}'
                            if summary['kind'] == 'free_bodies' else None),
        'bodies': bodies,
        'meshes': [],
        'frames': {'count': int(len(idx)), 'rule': rule, 't': f32(col['t'][idx]), 'bodies': frames_bodies},
        'series': series,
        'size': {'max_frames': a.max_frames, 'bytes_note': 'float32, decimated by the rule above'},
    }
    js = open(f'{a.bundle}/report.js').read()
    css = open(f'{a.bundle}/report.css').read()
    text = json.dumps(report, separators=(',', ':')).replace('</', '<\\/')
    with open(a.out, 'w') as f:
        f.write(f'<!doctype html><html lang="en"><head><meta charset="utf-8"><title>rigid — '
                f'{report["scene"]["name"]}</title><style>{css}</style></head><body>'
                f'<script type="application/json" id="rigid-report-data">{text}</script>'
                f'<script>{js}</script></body></html>')


if __name__ == '__main__':
    sys.exit(main())
