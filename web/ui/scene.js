// The 3D view: one flat-shaded mesh with per-face colours, an optional wireframe, orbit
// controls, and rendering on demand (an idle page draws nothing).
import * as THREE from '../vendor/three/three.module.js';
import { OrbitControls } from '../vendor/three/addons/controls/OrbitControls.js';

export function createScene(host) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  host.append(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f5f7);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = true;
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 2, 1.5);
  camera.add(sun);
  scene.add(camera);
  const material = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.75, metalness: 0, side: THREE.DoubleSide,
    flatShading: true, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  const wireMaterial = new THREE.MeshBasicMaterial({ color: 0x20242c, wireframe: true, transparent: true, opacity: 0.25 });
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
    requestRender();
  }

  // The colour array (9 floats per face) to fill, then colorsChanged().
  const colours = () => surface.geometry.getAttribute('color').array;
  function coloursChanged() {
    surface.geometry.getAttribute('color').needsUpdate = true;
    requestRender();
  }

  function frame() {
    const sphere = surface.geometry.boundingSphere;
    const distance = (sphere.radius / Math.sin((camera.fov * Math.PI) / 360)) * 1.15;
    controls.target.copy(sphere.center);
    camera.position.copy(sphere.center).add(new THREE.Vector3(0.55, 0.45, 0.75).normalize().multiplyScalar(distance));
    camera.near = distance / 100;
    camera.far = distance * 10;
    camera.updateProjectionMatrix();
    requestRender();
  }

  const raycaster = new THREE.Raycaster(), pointer = new THREE.Vector2();
  // The face under a pointer event, or -1.
  function pick(event) {
    const rect = renderer.domElement.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    return raycaster.intersectObject(surface)[0]?.faceIndex ?? -1;
  }

  return {
    canvas: renderer.domElement,
    setGeometry, colours, coloursChanged, frame, pick, requestRender,
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
