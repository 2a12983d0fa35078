// three.js's AnimationMixer as an oracle for the engine's blended poses.
//
//   node tests/mixer/mixer.mjs NODE_MODULES SPEC.json
//
// SPEC: {"model": path, "layers": [{"clip": name or index, "weight": w, "additive": bool}],
//        "transitions": [{"at": s, "to": name or index, "duration": s}], "times": [s, ...]}
// Each layer is an action playing from time 0, repeating, at its weight; an additive layer's clip
// goes through AnimationUtils.makeClipAdditive (its first frame the reference). At a transition's
// time, a fresh action of its clip starts and every playing action without addition crossfades to
// it (crossFadeTo, warp off). The mixer steps from time to time in order. Prints JSON: per time,
// every node's world position (model space) and every morphing node's weights, by glTF node index.
import fs from 'node:fs';
import path from 'node:path';

const [modules, specPath] = process.argv.slice(2);
if (!modules || !specPath) {
    console.error('usage: mixer.mjs NODE_MODULES SPEC.json');
    process.exit(2);
}
const THREE = await import(path.resolve(modules, 'three/build/three.module.js'));
const { GLTFLoader } = await import(path.resolve(modules, 'three/examples/jsm/loaders/GLTFLoader.js'));

// Node has no XMLHttpRequest and no file:// fetch: buffers a .gltf names are read from disk.
THREE.FileLoader.prototype.load = function (url, onLoad, _onProgress, onError) {
    fs.promises.readFile(decodeURIComponent(url)).then(
        (bytes) => onLoad(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength)),
        (error) => onError && onError(error));
};

const spec = JSON.parse(fs.readFileSync(specPath, 'utf8'));
const bytes = fs.readFileSync(spec.model);
const loader = new GLTFLoader();
// Poses need no images (and Node cannot decode them): every texture is an empty one.
loader.register(() => ({ name: 'glass_no_textures', loadTexture: () => Promise.resolve(new THREE.Texture()) }));
const gltf = await new Promise((resolve, reject) =>
    loader.parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength),
                 path.dirname(spec.model) + '/', resolve, reject));

const clipNamed = (name) => {
    const clip = typeof name === 'number' ? gltf.animations[name]
                                          : gltf.animations.find((c) => c.name === name);
    if (!clip)
        throw new Error(`no clip ${JSON.stringify(name)} in ${spec.model}`);
    return clip.clone(); // a clone is a new action, however often the clip plays
};

const root = gltf.scene;
const mixer = new THREE.AnimationMixer(root);
const blended = [];
for (const layer of spec.layers) {
    let clip = clipNamed(layer.clip);
    if (layer.additive)
        clip = THREE.AnimationUtils.makeClipAdditive(clip);
    const action = mixer.clipAction(clip);
    action.setEffectiveWeight(layer.weight ?? 1);
    action.play();
    if (!layer.additive)
        blended.push(action);
}

// Nodes by glTF index; a mesh node of several primitives is a group: its first mesh's weights.
const nodes = [];
root.traverse((object) => {
    const association = gltf.parser.associations.get(object);
    if (association && association.nodes !== undefined)
        nodes.push([association.nodes, object]);
});
const weightsOf = (object) => {
    if (object.morphTargetInfluences)
        return object.morphTargetInfluences;
    const mesh = object.children.find((c) => c.morphTargetInfluences);
    return mesh ? mesh.morphTargetInfluences : null;
};

const events = [
    ...spec.times.map((time, index) => ({ time, sample: index })),
    ...(spec.transitions ?? []).map((transition) => ({ time: transition.at, transition })),
].sort((a, b) => a.time - b.time || (a.transition ? -1 : 1));

const frames = new Array(spec.times.length);
let now = 0;
mixer.update(0);
for (const event of events) {
    if (event.time > now) {
        mixer.update(event.time - now);
        now = event.time;
    }
    if (event.transition) {
        const to = mixer.clipAction(clipNamed(event.transition.to));
        to.reset();
        to.setEffectiveWeight(1);
        to.play();
        for (const action of blended.splice(0))
            action.crossFadeTo(to, event.transition.duration, false);
        blended.push(to);
        continue;
    }
    root.updateMatrixWorld(true);
    const frame = { time: event.time, positions: {}, weights: {} };
    const position = new THREE.Vector3();
    for (const [index, object] of nodes) {
        position.setFromMatrixPosition(object.matrixWorld);
        frame.positions[index] = [position.x, position.y, position.z];
        const weights = weightsOf(object);
        if (weights)
            frame.weights[index] = Array.from(weights);
    }
    frames[event.sample] = frame;
}
process.stdout.write(JSON.stringify({ three: THREE.REVISION, frames }) + '\n');
