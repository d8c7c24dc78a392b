# Sourced by the bench scripts: bunny_scene MESH RENDER writes the Stanford bunny on a plane (the
# scene of bench/cluster-efficiency.sh and bench/viewer-benchmark.sh) to standard output, with
# RENDER as its render: mapping, e.g. "{width: 1280, height: 720}".
bunny_scene() {
  cat << SCENE
camera: {position: [0, 0.12, 0.32], look_at: [-0.02, 0.09, 0], up: [0, 1, 0], fov: 40}
render: $2
materials:
  floor: {color: 0.6, ambient: 0.1, diffuse: 0.7, specular: 0.3, shininess: 50}
  bunny: {color: [0.8, 0.7, 0.5], ambient: 0.1, diffuse: 0.7, specular: 0.6, shininess: 100}
lights: [{type: point, position: [0.5, 1, 1], intensity: 1}]
objects:
  - {type: plane, normal: [0, 1, 0], distance: 0.033, material: floor}
  - {type: mesh, file: $1, material: bunny}
SCENE
}
