// Reads a facecap glTF with three.js's own GLTFLoader (run as `node
// gltf_probe.mjs GLB OUT.json TIMES VERTICES`: TIMES and VERTICES comma
// separated) and writes to OUT.json what a three.js app would see: the scene's
// objects, the animation's tracks, the face mesh's morph target names and,
// at each time in seconds in turn (the AnimationMixer set there), where each vertex
// of the face's first part (by its index in that part) lands in the glTF
// camera's normalised device coordinates. The morph targets are applied as
// three.js's shaders apply them (base + sum of influence x target, the
// targets relative, as GLTFLoader marks them), on the CPU. Textures are not
// decoded (node has no image decoder); the loader goes on without them.
// threejs_interop_test.cpp compares the points with the tracker's fit.
import fs from "fs";
import * as THREE from "three";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";

const [glbPath, outPath, timesArg, verticesArg] = process.argv.slice(2);
if (!verticesArg) {
  console.error("usage: node gltf_probe.mjs GLB OUT.json TIMES VERTICES");
  process.exit(2);
}
const times = timesArg.split(",").map(Number);
const vertices = verticesArg.split(",").map(Number);
const bytes = fs.readFileSync(glbPath);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);

// Textures cannot be decoded under node: GLTFLoader reports each and carries on.
const quiet = console.error;
console.error = (...args) => {
  if (!String(args[0]).includes("Couldn't load texture")) quiet(...args);
};

new GLTFLoader().parse(
  buffer,
  "",
  (gltf) => {
    const objects = [];
    gltf.scene.traverse((o) => objects.push(`${o.type}:${o.name}`));
    const meshes = [];
    gltf.scene.traverse((o) => o.isMesh && meshes.push(o));
    const face = meshes[0];  // the first primitive: the face's skin
    const camera = gltf.cameras[0];
    const clip = gltf.animations[0];
    const mixer = new THREE.AnimationMixer(gltf.scene);
    mixer.clipAction(clip).play();
    const geometry = face.geometry;
    const base = geometry.attributes.position;
    const targets = geometry.morphAttributes.position || [];
    const report = {
      objects,
      tracks: clip.tracks.map((t) => t.name),
      morph_targets: Object.keys(face.morphTargetDictionary || {}),
      morph_relative: geometry.morphTargetsRelative,
      camera: { type: camera.type, aspect: camera.aspect, fov: camera.fov },
      images: (gltf.parser.json.images || []).map((i) => i.name || null),
      ndc: [],
    };
    for (const t of times) {
      mixer.setTime(t);
      gltf.scene.updateMatrixWorld(true);
      camera.updateMatrixWorld(true);
      const influences = face.morphTargetInfluences;
      report.ndc.push(vertices.map((i) => {
        const p = new THREE.Vector3().fromBufferAttribute(base, i);
        targets.forEach((target, k) => {
          const w = influences[k];
          if (w !== 0) p.addScaledVector(new THREE.Vector3().fromBufferAttribute(target, i), w);
        });
        p.applyMatrix4(face.matrixWorld).project(camera);
        return [p.x, p.y, p.z];
      }));
    }
    fs.writeFileSync(outPath, JSON.stringify(report));
  },
  (error) => {
    quiet(`gltf_probe: ${glbPath}: ${error.message || error}`);
    process.exit(1);
  },
);
