// The 3D view: one flat-shaded mesh with per-face colours, an optional wireframe, orbit
// controls, standard views in a Y- or Z-up frame, a section plane, face visibility, and
// rendering on demand (an idle page draws nothing).
import * as THREE from '../vendor/three/three.module.js';
import { OrbitControls } from '../vendor/three/addons/controls/OrbitControls.js';

export function createScene(host) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.localClippingEnabled = true;
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  host.append(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(matchMedia('(prefers-color-scheme: dark)').matches ? 0x1c2027 : 0xf4f5f7);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = true;
  // Reachable by keyboard: focused, the arrow keys pan.
  renderer.domElement.tabIndex = 0;
  controls.listenToKeyEvents(renderer.domElement);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 2, 1.5);
  camera.add(sun);
  scene.add(camera);
  const material = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.75, metalness: 0, side: THREE.DoubleSide,
    flatShading: true, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  const wireMaterial = new THREE.MeshBasicMaterial({ color: 0x20242c, wireframe: true, transparent: true, opacity: 0.25 });
  // The section: what lies above a plane across the up axis is cut away (double-sided
  // faces show the inside).
  const section = new THREE.Plane();
  let sectionAt = null;  // in [0, 1] from the model's bottom to its top, or null: none
  const surface = new THREE.Mesh(new THREE.BufferGeometry(), material);
  const wire = new THREE.Mesh(surface.geometry, wireMaterial);
  wire.visible = false;
  scene.add(surface, wire);

  let alive = true, frameRequested = false;
  // One frame per change (a camera move, new colours or geometry), and more only while
  // the controls' damping still moves the camera.
  function requestRender() {
    if (frameRequested || !alive) return;
    frameRequested = true;
    requestAnimationFrame(() => {
      frameRequested = false;
      if (!alive) return;
      if (controls.update()) requestRender();
      renderer.render(scene, camera);
    });
  }
  controls.addEventListener('change', requestRender);

  const observer = new ResizeObserver(() => {
    const w = host.clientWidth || 1, h = host.clientHeight || 1;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    requestRender();
  });
  observer.observe(host);

  // Unshared vertices, three per face, so that each face takes its own colour.
  function setGeometry(positions, triangles) {
    const n = triangles.length / 3, xyz = new Float32Array(9 * n);
    for (let f = 0; f < n; ++f)
      for (let k = 0; k < 3; ++k) {
        const v = triangles[3 * f + k];
        xyz.set(positions.subarray(3 * v, 3 * v + 3), 9 * f + 3 * k);
      }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(9 * n), 3));
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    surface.geometry.dispose();
    surface.geometry = wire.geometry = geometry;
    visibleFaces = null;
    placeSection();
  }

  // The colour array (9 floats per face) to fill, then colorsChanged().
  const colours = () => surface.geometry.getAttribute('color').array;
  function coloursChanged() {
    surface.geometry.getAttribute('color').needsUpdate = true;
    requestRender();
  }

  // Views in the model's own frame: right, up (Y or Z, a display setting) and towards the
  // viewer.
  let upAxis = 'y';
  const basis = () => (upAxis === 'z'
    ? [new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 0, 1), new THREE.Vector3(0, -1, 0)]
    : [new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 1, 0), new THREE.Vector3(0, 0, 1)]);
  const VIEWS = { iso: [0.55, 0.45, 0.75], front: [0, 0, 1], top: [0, 1, 0.001], side: [1, 0, 0] };
  let direction = 'iso';

  // Frames the faces `keep(face)` accepts (all without it) from the current direction.
  function frame(keep = null) {
    let sphere = surface.geometry.boundingSphere;
    if (keep) {
      const xyz = surface.geometry.getAttribute('position').array, points = [];
      for (let f = 0; f < xyz.length / 9; ++f)
        if (keep(f)) for (let k = 0; k < 3; ++k) points.push(new THREE.Vector3().fromArray(xyz, 9 * f + 3 * k));
      if (points.length) sphere = new THREE.Sphere().setFromPoints(points);
    }
    if (!sphere || !(sphere.radius > 0)) return;
    const [r, u, t] = basis(), [a, b, c] = VIEWS[direction];
    const towards = r.multiplyScalar(a).add(u.clone().multiplyScalar(b)).add(t.multiplyScalar(c)).normalize();
    const distance = (sphere.radius / Math.sin((camera.fov * Math.PI) / 360)) * 1.15;
    camera.up.copy(u);
    controls.target.copy(sphere.center);
    camera.position.copy(sphere.center).addScaledVector(towards, distance);
    camera.near = distance / 100;
    camera.far = distance * 10;
    camera.updateProjectionMatrix();
    controls.update();
    requestRender();
  }

  function placeSection() {
    const clipping = sectionAt === null ? [] : [section];
    material.clippingPlanes = wireMaterial.clippingPlanes = clipping;
    if (sectionAt !== null) {
      surface.geometry.computeBoundingBox();
      const box = surface.geometry.boundingBox, up = basis()[1];
      const low = Math.min(up.dot(box.min), up.dot(box.max)), high = Math.max(up.dot(box.min), up.dot(box.max));
      section.set(up.clone().negate(), low + sectionAt * (high - low));
    }
    requestRender();
  }

  // Only these faces are drawn and picked (null: all).
  let visibleFaces = null;
  function setVisibleFaces(faces) {
    visibleFaces = faces;
    const geometry = surface.geometry;
    if (!faces) geometry.setIndex(null);
    else {
      const index = new Uint32Array(3 * faces.length);
      faces.forEach((f, i) => index.set([3 * f, 3 * f + 1, 3 * f + 2], 3 * i));
      geometry.setIndex(new THREE.BufferAttribute(index, 1));
    }
    requestRender();
  }

  const raycaster = new THREE.Raycaster(), pointer = new THREE.Vector2();
  // The face under a pointer event, or -1.
  function pick(event) {
    const rect = renderer.domElement.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    const face = raycaster.intersectObject(surface)[0]?.faceIndex ?? -1;
    return face >= 0 && visibleFaces ? visibleFaces[face] : face;
  }

  return {
    canvas: renderer.domElement,
    setGeometry, colours, coloursChanged, frame, pick, setVisibleFaces,
    // 'y' or 'z': which model axis points up; the view is framed again.
    setUp(axis) {
      upAxis = axis;
      placeSection();
      frame();
    },
    // Cuts the model at `at` of its height along the up axis (0 bottom, 1 top), or not (null).
    setSection(at) {
      sectionAt = at;
      placeSection();
    },
    // 'iso', 'front', 'top' or 'side', in the model's up frame.
    view(name) {
      direction = name;
      frame();
    },
    // The picture as drawn, PNG.
    screenshot() {
      renderer.render(scene, camera);
      return new Promise((resolve) => renderer.domElement.toBlob(resolve, 'image/png'));
    },
    setWireframe(on) {
      wire.visible = on;
      requestRender();
    },
    destroy() {
      alive = false;
      observer.disconnect();
      controls.dispose();
      surface.geometry.dispose();
      renderer.dispose();
    },
  };
}
