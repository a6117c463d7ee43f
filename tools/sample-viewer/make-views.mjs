#!/usr/bin/env node
// Writes views.json: for every sample model with a glTF/ variant, the camera and lights that both
// the Khronos Sample Viewer (render-references.mjs) and fe's comparison test use.
// Usage: node make-views.mjs [--assets /work/shared/assets] [--out views.json]
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import {
  defaultSceneIndex, walkScene, worldBounds, fileLights, expandInstancing, lookAtCameraMatrix,
  xformPoint, xformDir, normalize, add, sub, scale, dot, len,
} from './gltf-util.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const arg = (name, def) => { const i = process.argv.indexOf(name); return i > 0 ? process.argv[i + 1] : def; };
const assets = path.resolve(arg('--assets', path.resolve(here, '../../../shared/assets')));
const outFile = path.resolve(arg('--out', path.join(here, 'views.json')));
const viewerVersion = JSON.parse(fs.readFileSync(path.join(here, 'package.json'))).dependencies['@khronosgroup/gltf-viewer'];

const YFOV = 0.6;
const VIEW_DIR = normalize([0.5, 0.45, 1.0]);    // from target towards eye: +Z front, +X right, +Y up
const MARGIN = 1.05;
const RIG = [
  { name: 'fe_key', type: 'directional', color: [1, 1, 1], intensity: 3, direction: normalize([-0.4, -0.8, -0.45]) },
  { name: 'fe_fill', type: 'directional', color: [1, 1, 1], intensity: 1, direction: normalize([0.6, -0.3, 0.7]) },
];
const r6 = x => Number(x.toPrecision(9));           // keep the JSON readable; float32-exact enough
const rv = v => v.map(r6);

const models = [], skipped = [];
for (const name of fs.readdirSync(assets).sort()) {
  const dir = path.join(assets, name);
  if (!fs.statSync(dir).isDirectory() || name === 'LICENSES') continue;
  const gdir = path.join(dir, 'glTF');
  const gltfs = fs.existsSync(gdir) ? fs.readdirSync(gdir).filter(f => f.endsWith('.gltf')) : [];
  if (gltfs.length === 0) {
    const variants = fs.readdirSync(dir).filter(f => f.startsWith('glTF'));
    skipped.push({ name, reason: `no glTF/ folder (only ${variants.join(', ') || 'nothing'})` });
    continue;
  }
  const file = gltfs.includes(`${name}.gltf`) ? `${name}.gltf` : gltfs[0];
  const rel = `${name}/glTF/${file}`;
  let json = JSON.parse(fs.readFileSync(path.join(gdir, file), 'utf8'));
  const notes = [];
  if ((json.extensionsRequired ?? []).includes('KHR_draco_mesh_compression')) {
    skipped.push({ name, reason: 'glTF/ variant needs KHR_draco_mesh_compression' });
    continue;
  }
  const instances = expandInstancing(json, gdir);
  if (instances) notes.push(`EXT_mesh_gpu_instancing (not implemented by the viewer) was expanded into ${instances} child nodes of the instanced node before rendering; bounds include every instance`);
  const sceneIndex = defaultSceneIndex(json);
  if ((json.scenes ?? []).length > 1) notes.push(`file has ${json.scenes.length} scenes; only the default scene ${sceneIndex} is rendered`);
  if ((json.animations ?? []).length) notes.push('animations present: none is applied (rest pose: node TRS and weights as stored in the file)');
  if ((json.skins ?? []).length) notes.push('skinned: joints at their rest-pose node transforms; bounds ignore the skin (mesh node transform used)');
  const bounds = worldBounds(json, sceneIndex);
  if (!bounds) { skipped.push({ name, reason: 'default scene has no mesh' }); continue; }

  // camera
  let camNode = null;
  walkScene(json, sceneIndex, (i, world, node) => {
    if (camNode === null && node.camera !== undefined) camNode = { i, world, node };
  });
  let camera;
  if (camNode && json.cameras[camNode.node.camera].type === 'perspective') {
    const c = json.cameras[camNode.node.camera];
    const eye = xformPoint(camNode.world, [0, 0, 0]);
    const fwd = normalize(xformDir(camNode.world, [0, 0, -1]));
    const upRaw = xformDir(camNode.world, [0, 1, 0]);
    const up = normalize(sub(upRaw, scale(fwd, dot(upRaw, fwd))));
    let dist = dot(sub(bounds.center, eye), fwd);
    if (!(dist > 0)) dist = 1;
    const target = add(eye, scale(fwd, dist));
    camera = {
      source: 'file', fileCameraNode: camNode.i, fileCamera: camNode.node.camera,
      eye: rv(eye), target: rv(target), up: rv(up),
      yfov: c.perspective.yfov, znear: c.perspective.znear, zfar: c.perspective.zfar ?? null,
    };
    if (c.perspective.aspectRatio !== undefined) {
      camera.fileAspectRatio = c.perspective.aspectRatio;
      notes.push(`file camera's aspectRatio ${r6(c.perspective.aspectRatio)} is not used: both renderers use the image's 320/240`);
    }
    if (camera.zfar === null) notes.push('file camera has no zfar: infinite projection');
  } else {
    if (camNode) notes.push('first camera is orthographic: framed with the default rule instead');
    const distance = bounds.radius / Math.sin(YFOV / 2) * MARGIN;
    camera = {
      source: 'framed',
      eye: rv(add(bounds.center, scale(VIEW_DIR, distance))), target: rv(bounds.center), up: [0, 1, 0],
      yfov: YFOV, znear: r6(distance / 100), zfar: r6(distance * 100), distance: r6(distance),
    };
  }
  camera.aspectRatio = 320 / 240;
  camera.matrix = rv(lookAtCameraMatrix(camera.eye, camera.target, camera.up));

  // lights
  const own = fileLights(json, sceneIndex);
  const lightsFromFile = own.length > 0 || (json.extensions?.KHR_lights_punctual?.lights ?? []).length > 0;
  const lights = lightsFromFile
    ? own.map(l => ({ ...l, position: rv(l.position), direction: rv(l.direction) }))
    : RIG.map(l => ({ ...l, direction: rv(l.direction) }));
  if (lightsFromFile && own.length === 0) notes.push('file defines KHR_lights_punctual lights but none is in the default scene: rendered unlit');

  models.push({
    name, gltf: rel, scene: sceneIndex, reference: `${name}.png`, referenceToneMapNone: `tonemap-none/${name}.png`,
    camera, lightsFromFile, lights,
    bounds: { min: rv(bounds.min), max: rv(bounds.max), center: rv(bounds.center), radius: r6(bounds.radius) },
    ...(notes.length ? { notes } : {}),
  });
}

const manifest = {
  schemaVersion: 1,
  description: 'Views of the Khronos glTF sample models for reference renders: see docs/SAMPLE_VIEWER.md',
  assetsRoot: '/work/shared/assets (paths below are relative to it)',
  viewer: { package: '@khronosgroup/gltf-viewer', version: viewerVersion, browser: 'Debian chromium, WebGL2 on SwiftShader (ANGLE/Vulkan)' },
  image: {
    width: 320, height: 240, devicePixelRatio: 1, format: 'PNG, 8-bit RGB, rows top to bottom, no colour chunks',
    encoding: 'viewer output: linear radiance * exposure -> tone map -> pow(c, 1/2.2) (the viewer\'s linearTosRGB, a 2.2 gamma, not the piecewise sRGB curve) -> clamp -> 8-bit UNORM',
    antialias: false,
  },
  rendering: {
    toneMap: 'Khronos PBR Neutral', exposure: 1, toneMapNoneVariant: 'None (Linear mapping, clamped at 1.0)',
    useIBL: false, useDirectionalLightsWithDisabledIBL: false, usePunctual: true, renderEnvironmentMap: false,
    clearColor: [0, 0, 0, 1], internalMSAA: 0, animations: 'none applied (rest pose)', morphing: true, skinning: true,
    textureDecode: 'baseColor/emissive textures uploaded as SRGB8_ALPHA8 (exact sRGB decode by the GPU), others as RGBA8',
  },
  viewerBehaviour: [
    'output = pow(toneMap(color * exposure), 1/2.2) for every material, KHR_materials_unlit and emissive included (unlit white 1.0 -> PBR Neutral 0.869 -> 239/255)',
    'Khronos PBR Neutral as in the Khronos reference: startCompression 0.76, desaturation 0.15, offset x - 6.25x^2 below 0.08 else 0.04',
    'punctual: radiance = sum(intensity * color * attenuation * BRDF * NdotL); Lambert = baseColor / pi; point/spot attenuation 1/d^2 without range, clamp(1 - (d/range)^4, 0, 1) / d^2 with range; spot smooth factor squared between outer and inner cone cos',
    'IBL off: environment intensity forced to 0, so metals show only their punctual highlights (black elsewhere)',
    'primitives with NORMAL and TEXCOORD_0 but no TANGENT get MikkTSpace tangents (mesh unwelded first); primitives without NORMAL use flat normals from screen-space derivatives of the world position',
    'double-sided: back faces flip the shading normal (gl_FrontFacing); world matrices with negative determinant swap the front face winding',
    'COLOR_0 (vec3 or vec4) multiplies the base colour',
    'opaque and MASK primitives drawn in scene-node order without sorting; BLEND primitives sorted back to front by the view-space depth of each primitive\'s centroid; BLEND uses SRC_ALPHA, ONE_MINUS_SRC_ALPHA',
    'POINTS drawn with gl_PointSize 1, LINES 1 pixel wide; without NORMAL they are unlit (base colour + emissive)',
    'primitives without a material get the viewer\'s default material (white, metallic 1, roughness 1 per glTF defaults)',
    'textures: base colour and emissive uploaded as SRGB8_ALPHA8, the rest as RGBA8, mipmaps generated when the sampler asks for them; images decoded by Chromium without colour-space conversion',
  ],
  cameraConventions: 'glTF: right-handed, +Y up, camera looks down its local -Z. eye/target/up in world space; matrix = camera-to-world (column-major), equal to the inverse of lookAt(eye, target, up). Perspective, aspectRatio = 320/240, OpenGL clip depth.',
  cameraRule: {
    fileCamera: 'first camera node met in a depth-first, pre-order walk of the default scene (perspective only): its world transform, yfov, znear, zfar; target = eye + forward * (distance from eye to bounds centre along forward)',
    framed: 'target = centre of the world AABB of the default scene (POSITION min/max through node transforms); eye = target + normalize(0.5, 0.45, 1.0) * distance; distance = radius / sin(yfov / 2) * 1.05, radius = half the AABB diagonal; yfov 0.6; znear = distance / 100; zfar = distance * 100; up = +Y',
  },
  lightRule: 'If the file defines KHR_lights_punctual lights, only the lights of its default scene are used (lightsFromFile: true, listed here in world space for information). Otherwise the fixed rig below is injected as KHR_lights_punctual nodes at the scene root. Directional intensity in lux, point/spot in candela; direction = direction of travel of the light (node -Z).',
  lightRig: RIG.map(l => ({ ...l, direction: rv(l.direction) })),
  models,
  skipped,
};
// numeric arrays on one line each
const text = JSON.stringify(manifest, null, 2)
  .replace(/\[\s*(-?[\d.e+-]+(?:,\s*-?[\d.e+-]+)*)\s*\]/g, (m, body) => `[${body.split(/,\s*/).join(', ')}]`);
fs.writeFileSync(outFile, text + '\n');
console.log(`wrote ${outFile}: ${models.length} models, ${skipped.length} skipped`);
