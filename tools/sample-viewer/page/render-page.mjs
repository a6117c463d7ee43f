// Browser side: loads one glTF into the Khronos glTF Sample Viewer and returns the canvas pixels.
import { GltfView, GltfState } from '/viewer/gltf-viewer.module.js';

const canvas = document.getElementById('canvas');

function toBase64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

let gl = null, view = null, loader = null, state = null;

// Called once per page. The renderer needs a loaded environment even with IBL off (it binds the
// environment's textures for every draw, and the transmission path reads its GGX LUT), so a black
// panorama is loaded: the viewer prefilters it on the GPU (GGX/Charlie LUTs computed as usual), and
// with useIBL=false its intensity is forced to 0.
// init: { envUrl, sheenLutUrl }
window.feInit = async (init) => {
  gl = canvas.getContext('webgl2', {
    alpha: false, antialias: false, depth: true, stencil: false,
    premultipliedAlpha: true, preserveDrawingBuffer: true, powerPreference: 'default',
  });
  if (!gl) throw new Error('no WebGL2 context');
  const dbg = gl.getExtension('WEBGL_debug_renderer_info');
  const renderer = gl.getParameter(dbg ? dbg.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
  view = new GltfView(gl);
  loader = view.createResourceLoader(undefined, undefined, '/viewer/libs/');
  state = view.createState();
  const t0 = performance.now();
  state.environment = await loader.loadEnvironment(init.envUrl, { lut_sheen_E_file: init.sheenLutUrl });
  return { renderer, environmentSeconds: (performance.now() - t0) / 1000, devicePixelRatio: window.devicePixelRatio };
};

// opts: { url, sceneIndex, cameraIndex, toneMaps: [name, ...] }
// returns { width, height, images: [{ toneMap, rgba (base64, bottom row first) }], repeatIdentical, stats }
window.feRender = async (opts) => {
  state.gltf = await loader.loadGltf(opts.url);
  state.sceneIndex = opts.sceneIndex;
  state.cameraIndex = opts.cameraIndex;
  state.animationIndices = [];          // no animation plays: every animated property at its rest value
  state.internalMSAA = 0;               // the renderer reads this (not renderingParameters.internalMSAA) for its transmission buffer
  const p = state.renderingParameters;
  p.useIBL = false;
  p.renderEnvironmentMap = false;
  p.useDirectionalLightsWithDisabledIBL = false;
  p.usePunctual = true;
  p.exposure = 1.0;
  p.clearColor = [0, 0, 0, 1];          // passed straight to gl.clearColor (so 0..1, despite the doc's 0..255)
  p.internalMSAA = 0;
  p.morphing = true;
  p.skinning = true;
  p.debugOutput = GltfState.DebugOutput.NONE;

  const w = canvas.width, h = canvas.height;
  const grab = () => {
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return px;
  };
  const images = [];
  let first = null, repeatIdentical = null;
  for (const toneMap of opts.toneMaps) {
    if (!Object.values(GltfState.ToneMaps).includes(toneMap)) throw new Error(`unknown tone map ${toneMap}`);
    p.toneMap = toneMap;
    view.renderFrame(state, w, h);
    const px = grab();
    if (first === null) first = px;
    images.push({ toneMap, rgba: toBase64(px) });
  }
  // render the first setting once more: the frame must not depend on anything but the state
  p.toneMap = opts.toneMaps[0];
  view.renderFrame(state, w, h);
  const again = grab();
  repeatIdentical = again.every((v, i) => v === first[i]);
  const stats = view.gatherStatistics(state);
  return { width: w, height: h, images, repeatIdentical, stats };
};
window.feReady = true;
