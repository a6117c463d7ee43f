// Small glTF helpers shared by make-views.mjs and render-references.mjs:
// column-major 4x4 matrices (glTF convention), scene traversal, world bounds,
// and the JSON edits that inject a camera, lights and expanded instances.
import fs from 'node:fs';
import path from 'node:path';

export const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

export function mul(a, b) {
  const r = new Array(16).fill(0);
  for (let c = 0; c < 4; ++c)
    for (let row = 0; row < 4; ++row) {
      let s = 0;
      for (let k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  return r;
}

export function fromTRS(t = [0, 0, 0], q = [0, 0, 0, 1], s = [1, 1, 1]) {
  const [x, y, z, w] = q;
  const xx = x * x, yy = y * y, zz = z * z, xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
  return [
    (1 - 2 * (yy + zz)) * s[0], 2 * (xy + wz) * s[0], 2 * (xz - wy) * s[0], 0,
    2 * (xy - wz) * s[1], (1 - 2 * (xx + zz)) * s[1], 2 * (yz + wx) * s[1], 0,
    2 * (xz + wy) * s[2], 2 * (yz - wx) * s[2], (1 - 2 * (xx + yy)) * s[2], 0,
    t[0], t[1], t[2], 1,
  ];
}

export function localMatrix(node) {
  if (node.matrix) return node.matrix.slice();
  return fromTRS(node.translation, node.rotation, node.scale);
}

export function xformPoint(m, p) {
  return [0, 1, 2].map(i => m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i]);
}
export function xformDir(m, d) {
  return [0, 1, 2].map(i => m[i] * d[0] + m[4 + i] * d[1] + m[8 + i] * d[2]);
}
export const sub = (a, b) => a.map((v, i) => v - b[i]);
export const add = (a, b) => a.map((v, i) => v + b[i]);
export const scale = (a, s) => a.map(v => v * s);
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const len = a => Math.sqrt(dot(a, a));
export const normalize = a => scale(a, 1 / len(a));

// Camera-to-world matrix of a right-handed camera at eye looking at target (-Z forward, +Y up),
// the same basis gluLookAt/glm::lookAt invert to.
export function lookAtCameraMatrix(eye, target, up) {
  const zAxis = normalize(sub(eye, target));
  const xAxis = normalize(cross(up, zAxis));
  const yAxis = cross(zAxis, xAxis);
  return [...xAxis, 0, ...yAxis, 0, ...zAxis, 0, ...eye, 1];
}

// Orthonormal node matrix whose local -Z points along `direction` (for directional/spot lights).
export function lightNodeMatrix(direction, position = [0, 0, 0]) {
  const zAxis = normalize(scale(direction, -1));
  const helper = Math.abs(zAxis[1]) > 0.99 ? [1, 0, 0] : [0, 1, 0];
  const xAxis = normalize(cross(helper, zAxis));
  const yAxis = cross(zAxis, xAxis);
  return [...xAxis, 0, ...yAxis, 0, ...zAxis, 0, ...position, 1];
}

export function defaultSceneIndex(json) {
  return json.scene ?? 0;
}

// Depth-first, pre-order walk of the default scene: cb(nodeIndex, worldMatrix, node).
export function walkScene(json, sceneIndex, cb) {
  const scene = (json.scenes ?? [])[sceneIndex];
  if (!scene) return;
  const visit = (i, parent) => {
    const node = json.nodes[i];
    const world = mul(parent, localMatrix(node));
    cb(i, world, node);
    for (const c of node.children ?? []) visit(c, world);
  };
  for (const n of scene.nodes ?? []) visit(n, IDENTITY);
}

// ----- accessor reading (only what EXT_mesh_gpu_instancing expansion needs) -----
const COMPONENTS = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT4: 16 };
const COMPONENT_INFO = {
  5120: [1, 'getInt8', 127], 5121: [1, 'getUint8', 255], 5122: [2, 'getInt16', 32767],
  5123: [2, 'getUint16', 65535], 5125: [4, 'getUint32', 0], 5126: [4, 'getFloat32', 0],
};
export function readAccessor(json, gltfDir, index) {
  const acc = json.accessors[index];
  if (acc.sparse) throw new Error('sparse instancing accessors are not supported');
  const view = json.bufferViews[acc.bufferView];
  const buf = json.buffers[view.buffer];
  if (!buf.uri || buf.uri.startsWith('data:')) throw new Error('only external buffers are supported');
  const bytes = fs.readFileSync(path.join(gltfDir, decodeURIComponent(buf.uri)));
  const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const n = COMPONENTS[acc.type];
  const [size, getter, norm] = COMPONENT_INFO[acc.componentType];
  const stride = view.byteStride ?? size * n;
  const base = (view.byteOffset ?? 0) + (acc.byteOffset ?? 0);
  const out = [];
  for (let i = 0; i < acc.count; ++i) {
    const v = [];
    for (let k = 0; k < n; ++k) {
      let x = dv[getter](base + i * stride + k * size, true);
      if (acc.normalized && norm) x = Math.max(x / norm, -1);
      v.push(x);
    }
    out.push(v);
  }
  return out;
}

// Replace every node's EXT_mesh_gpu_instancing by one child node per instance carrying the mesh
// with the instance's TRS (the extension's instance transform is applied in the node's local space,
// so the result is the same picture). Mutates and returns json; returns the number of instances made.
export function expandInstancing(json, gltfDir) {
  let made = 0;
  const originalCount = json.nodes?.length ?? 0;
  for (let i = 0; i < originalCount; ++i) {
    const node = json.nodes[i];
    const ext = node.extensions?.EXT_mesh_gpu_instancing;
    if (!ext || node.mesh === undefined) continue;
    const a = ext.attributes ?? {};
    const T = a.TRANSLATION !== undefined ? readAccessor(json, gltfDir, a.TRANSLATION) : null;
    const R = a.ROTATION !== undefined ? readAccessor(json, gltfDir, a.ROTATION) : null;
    const S = a.SCALE !== undefined ? readAccessor(json, gltfDir, a.SCALE) : null;
    const count = (T ?? R ?? S).length;
    node.children = node.children ?? [];
    for (let k = 0; k < count; ++k) {
      const child = { name: `${node.name ?? 'node' + i}_instance${k}`, mesh: node.mesh };
      if (T) child.translation = T[k];
      if (R) child.rotation = R[k];
      if (S) child.scale = S[k];
      if (node.skin !== undefined) child.skin = node.skin;
      if (node.weights !== undefined) child.weights = node.weights;
      node.children.push(json.nodes.length);
      json.nodes.push(child);
      ++made;
    }
    delete node.mesh;
    delete node.skin;
    delete node.weights;
    delete node.extensions.EXT_mesh_gpu_instancing;
    if (Object.keys(node.extensions).length === 0) delete node.extensions;
  }
  if (made) {
    json.extensionsUsed = (json.extensionsUsed ?? []).filter(e => e !== 'EXT_mesh_gpu_instancing');
    json.extensionsRequired = (json.extensionsRequired ?? []).filter(e => e !== 'EXT_mesh_gpu_instancing');
    if (!json.extensionsUsed.length) delete json.extensionsUsed;
    if (!json.extensionsRequired.length) delete json.extensionsRequired;
  }
  return made;
}

// World-space AABB of the default scene: each POSITION accessor's min/max box, its 8 corners
// through the node's world matrix (rest pose: node TRS as in the file, no animation/skin/morph).
export function worldBounds(json, sceneIndex) {
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  walkScene(json, sceneIndex, (i, world, node) => {
    if (node.mesh === undefined) return;
    for (const prim of json.meshes[node.mesh].primitives) {
      const acc = json.accessors[prim.attributes.POSITION];
      if (!acc?.min || !acc?.max) continue;
      for (let c = 0; c < 8; ++c) {
        const p = [0, 1, 2].map(k => ((c >> k) & 1) ? acc.max[k] : acc.min[k]);
        const w = xformPoint(world, p);
        for (let k = 0; k < 3; ++k) { min[k] = Math.min(min[k], w[k]); max[k] = Math.max(max[k], w[k]); }
      }
    }
  });
  if (!isFinite(min[0])) return null;
  const center = scale(add(min, max), 0.5);
  const radius = len(sub(max, min)) * 0.5;
  return { min, max, center, radius };
}

// KHR_lights_punctual lights instanced in the default scene, in world space.
export function fileLights(json, sceneIndex) {
  const defs = json.extensions?.KHR_lights_punctual?.lights ?? [];
  const out = [];
  walkScene(json, sceneIndex, (i, world, node) => {
    const li = node.extensions?.KHR_lights_punctual?.light;
    if (li === undefined) return;
    const d = defs[li];
    const light = {
      fromFile: true, node: i, lightIndex: li, name: d.name,
      type: d.type, color: d.color ?? [1, 1, 1], intensity: d.intensity ?? 1,
      position: xformPoint(world, [0, 0, 0]),
      direction: normalize(xformDir(world, [0, 0, -1])),
    };
    if (d.range !== undefined) light.range = d.range;
    if (d.type === 'spot') {
      light.innerConeAngle = d.spot?.innerConeAngle ?? 0;
      light.outerConeAngle = d.spot?.outerConeAngle ?? Math.PI / 4;
    }
    out.push(light);
  });
  return out;
}

// Adds the manifest's camera (and, unless fromFile, its lights) to a copy of the glTF JSON as new
// root nodes of the default scene. Returns { json, cameraIndex }.
export function injectView(json, view) {
  json = structuredClone(json);
  const sceneIndex = view.scene;
  const scene = json.scenes[sceneIndex];
  json.nodes = json.nodes ?? [];
  json.cameras = json.cameras ?? [];
  const cam = view.camera;
  const perspective = { yfov: cam.yfov, znear: cam.znear, zfar: cam.zfar };
  // no aspectRatio: the viewer then uses the viewport's 320/240 and fills the whole canvas
  const cameraIndex = json.cameras.length;
  json.cameras.push({ name: 'fe_reference_camera', type: 'perspective', perspective });
  scene.nodes.push(json.nodes.length);
  json.nodes.push({ name: 'fe_reference_camera', camera: cameraIndex, matrix: cam.matrix });
  if (!view.lightsFromFile && view.lights.length) {
    json.extensions = json.extensions ?? {};
    json.extensions.KHR_lights_punctual = json.extensions.KHR_lights_punctual ?? { lights: [] };
    const defs = json.extensions.KHR_lights_punctual.lights;
    json.extensionsUsed = [...new Set([...(json.extensionsUsed ?? []), 'KHR_lights_punctual'])];
    for (const l of view.lights) {
      const def = { name: l.name, type: l.type, color: l.color, intensity: l.intensity };
      if (l.range !== undefined) def.range = l.range;
      if (l.type === 'spot') def.spot = { innerConeAngle: l.innerConeAngle, outerConeAngle: l.outerConeAngle };
      scene.nodes.push(json.nodes.length);
      json.nodes.push({
        name: l.name,
        matrix: lightNodeMatrix(l.direction ?? [0, 0, -1], l.position ?? [0, 0, 0]),
        extensions: { KHR_lights_punctual: { light: defs.length } },
      });
      defs.push(def);
    }
  }
  return { json, cameraIndex };
}
