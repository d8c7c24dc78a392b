#!/bin/bash
# tools/gpu-check.sh — the CUDA back end checked and timed on a GPU (docs/gpu.md).
#
#   tools/gpu-check.sh prepare [build dir]
#       On the build machine (Debian, nvcc 13): builds strahl, strahl-diff and strahl-gpu-bench
#       for sm_90 + compute_90 PTX, AVX2 (no -march=native), without Embree and MPI, with three
#       variants of the render kernel (registers for 1, 3 and 4 blocks per SM: 255, 168, 128), into
#       [build dir] (default build-gpu), and packs them into .gpu/ with every shared library they
#       load (glibc and its loader included: they run through .gpu/lib/ld-linux-x86-64.so.2, so
#       the GPU machine's own libraries do not matter), the scenes, and the bunny and the dragon
#       (../shared/data). .gpu/ is ignored by git (.git/info/exclude); about 42 MB.
#   tools/gpu-check.sh run
#       On the GPU machine (the device tool: carry [".gpu"], command "bash tools/gpu-check.sh run"),
#       or here to rehearse: CPU references, then the GPU — which is where a machine without
#       one stops (exit 3, "FAIL at the GPU: …"). With a GPU: every scene on both devices,
#       compared (identical bytes for the grid sampler on the lecture scenes, RMSE ≤ 1e-6
#       elsewhere), then frames/s and Grays/s. Logs and images go under $OUT (the device tool's
#       folder) when it is set, else /tmp/strahl-gpu-check (not into .gpu/, which must stay small
#       to travel); the last lines are the table and a "GOAL met|MISSED" line per goal of issue 17.
#   tools/gpu-check.sh goals-of TABLE
#       The goal lines of a saved table (the run's last lines).
# Exit codes: 0 every check passed, 1 a comparison failed, 2 set-up (no bundle, a tool failed),
# 3 no usable GPU.
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
bundle=$here/.gpu

prepare() {
  set -e
  local build=${1:-$here/build-gpu}
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-/work} CCACHE_DIR=${CCACHE_DIR:-/work/.ccache}
  local launcher=()
  command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  mkdir -p "$build"
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSTRAHL_NATIVE=OFF -DCMAKE_CXX_FLAGS=-mavx2 \
    -DSTRAHL_BUILD_TESTS=OFF -DSTRAHL_BUILD_EXTRAS=OFF -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON \
    -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON "-DSTRAHL_CUDA_KERNEL_MIN_BLOCKS=1;3;4" "${launcher[@]}" > "$build/gpu-check-configure.log"
  grep -q "building the CUDA back end" "$build/gpu-check-configure.log" || { cat "$build/gpu-check-configure.log"; echo "prepare: CMake found no nvcc"; exit 2; }
  cmake --build "$build" -j"$(nproc)" --target strahl_cli strahl-diff strahl-gpu-bench
  rm -rf "$bundle"
  mkdir -p "$bundle/bin" "$bundle/lib" "$bundle/data"
  cp "$build/bin/strahl" "$build/bin/strahl-diff" "$build/bin/strahl-gpu-bench" "$bundle/bin/"
  # Every shared library the programs load, and the loader itself.
  local lib
  for lib in $(ldd "$bundle"/bin/* | awk '/=> \// {print $3} $1 ~ /^\/.*ld-linux/ {print $1}' | sort -u); do
    cp -L "$lib" "$bundle/lib/"
  done
  [ -e "$bundle/lib/ld-linux-x86-64.so.2" ] || { echo "prepare: no ld-linux-x86-64.so.2 among the libraries"; exit 2; }
  cp -r "$here/scenes" "$bundle/scenes"
  for mesh in stanford-bunny.obj dragon-100k.obj; do
    if [ -f "$here/../shared/data/$mesh" ]; then cp "$here/../shared/data/$mesh" "$bundle/data/"
    elif [ -f /work/shared/data/$mesh ]; then cp /work/shared/data/$mesh "$bundle/data/"
    else echo "prepare: $mesh not found (../shared/data): that scene will be skipped"; fi
  done
  git -C "$here" rev-parse HEAD > "$bundle/commit" 2> /dev/null || true
  local exclude
  exclude=$(git -C "$here" rev-parse --path-format=absolute --git-path info/exclude 2> /dev/null) \
    && { grep -qx '/.gpu/' "$exclude" 2> /dev/null || echo '/.gpu/' >> "$exclude"; }
  du -sh "$bundle"
  echo "prepare: .gpu/ is ready (commit $(cat "$bundle/commit" 2> /dev/null)); run it where the GPU is: bash tools/gpu-check.sh run"
}

# ---- run ----

out=${OUT:-${TMPDIR:-/tmp}/strahl-gpu-check}
table=()
failures=0
note() { table+=("$1"); echo "$1"; }

# A bundled program through the bundled loader; the driver's libcuda.so.1 found where the system keeps it.
libpath=$bundle/lib
find_driver() {
  local d ld=${LD_LIBRARY_PATH:-}
  for d in $(ldconfig -p 2> /dev/null | awk '/libcuda\.so\.1 / {print $NF}' | xargs -r -n1 dirname) /usr/local/nvidia/lib64 \
           /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu /usr/lib64 ${ld//:/ }; do
    [ -e "$d/libcuda.so.1" ] && [[ ":$libpath:" != *":$d:"* ]] && libpath=$libpath:$d
  done
}
tool() { local p=$1; shift; "$bundle/lib/ld-linux-x86-64.so.2" --library-path "$libpath" "$bundle/bin/$p" "$@"; }

# The meshes as scenes: the mesh on a grey floor under one light, the camera in front of it.
mesh_scene() {  # name file scale translate-y camera-z
  cat > "$out/$1.yaml" << SCENE
camera: {position: [0, 0.1, $5], look_at: [0, 0.1, 0], up: [0, 1, 0], fov: 40}
render: {width: 640, height: 360, max_depth: 4, background: [0.2, 0.25, 0.3]}
materials:
  model: {color: [0.8, 0.7, 0.5], ambient: 0.1, diffuse: 0.7, specular: 0.6, shininess: 100, reflectivity: 0.2}
  floor: {color: 0.6, ambient: 0.1, diffuse: 0.8}
lights:
  - {type: point, position: [3, 5, 6], intensity: 1}
objects:
  - {type: mesh, file: $2, material: model, scale: $3, translate: [0, $4, 0]}
  - {type: plane, normal: [0, 1, 0], distance: -0.6, material: floor}
SCENE
}

compare() {  # name exact|rmse cpu.pfm gpu.pfm
  local name=$1 mode=$2 a=$3 b=$4 line rc rmse
  line=$(tool strahl-diff "$a" "$b" 2>&1); rc=$?
  rmse=$(awk '/^rmse/ {print $2}' <<< "$line")
  if [ $rc != 0 ] || [ -z "$rmse" ]; then
    note "FAIL  $name: strahl-diff exited $rc ($line)"; failures=$((failures + 1))
  elif [ "$mode" = exact ]; then
    if cmp -s "$a" "$b"; then note "PASS  $name: identical bytes ($line)"
    else note "FAIL  $name: bytes differ ($line)"; failures=$((failures + 1)); fi
  elif [[ "$rmse" =~ ^[0-9.]+(e[-+]?[0-9]+)?$ ]] && awk -v r="$rmse" 'BEGIN {exit !(r + 0 <= 1e-6)}'; then
    note "PASS  $name: rmse ≤ 1e-6 ($line)"
  else
    note "FAIL  $name: rmse above 1e-6 ($line)"; failures=$((failures + 1))
  fi
}

# strahl-gpu-bench, its lines kept for the table.
bench() {
  local log l
  log=$(tool strahl-gpu-bench "$@" 2>&1) || { echo "$log"; note "FAIL  strahl-gpu-bench $*"; failures=$((failures + 1)); return; }
  echo "$log"
  while read -r l; do note "$l"; done < <(grep -h '^frame\|^kernel\|^primary\|^strahl-view benchmark' <<< "$log")
}

# The issue's goals, judged from the table's strahl-gpu-bench lines: one "GOAL met|MISSED" line each.
#   goal <kind: frame|primary> <scene file name> <figure: frames/s|Grays/s> <at least>
goal() {
  local kind=$1 scene=$2 unit=$3 least=$4 line value
  line=$(printf '%s\n' "${table[@]}" | grep -E "^$kind +$scene " | head -1)
  value=$(grep -oE "[0-9.]+ $unit" <<< "$line" | head -1 | cut -d' ' -f1)
  if [ -z "$value" ]; then echo "GOAL not measured  $kind $scene: ≥ $least $unit"
  elif awk -v v="$value" -v l="$least" 'BEGIN {exit !(v + 0 >= l + 0)}'; then echo "GOAL met     $kind $scene: $value $unit ≥ $least"
  else echo "GOAL MISSED  $kind $scene: $value $unit < $least"; fi
}
goals() {
  goal frame lecture-whitted.yaml frames/s 200
  goal frame lecture-distributed.yaml frames/s 10
  goal primary bunny.yaml Grays/s 1
  goal primary dragon.yaml Grays/s 1
  goal primary bumpy.yaml Grays/s 0.5
}

run() {
  [ -x "$bundle/lib/ld-linux-x86-64.so.2" ] || [ -e "$bundle/lib/ld-linux-x86-64.so.2" ] \
    || { echo "FAIL: no bundle at $bundle: run 'tools/gpu-check.sh prepare' on the build machine and carry .gpu"; exit 2; }
  mkdir -p "$out"
  find_driver
  echo "== gpu-check: bundle of commit $(cat "$bundle/commit" 2> /dev/null), $(date -u +%FT%TZ), $(uname -srm)"
  tool strahl --version || { echo "FAIL: the bundled strahl does not start here"; exit 2; }
  command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm --format=csv
  echo "libraries: $libpath"

  # Scenes: the lecture's three, the bunny and the dragon (where carried), on the CPU first.
  local scenes=() s
  for s in lecture lecture-whitted lecture-distributed; do cp "$bundle/scenes/$s.yaml" "$out/"; scenes+=("$s"); done
  [ -f "$bundle/data/stanford-bunny.obj" ] && { mesh_scene bunny "$bundle/data/stanford-bunny.obj" 8 -0.85 4; scenes+=(bunny); }
  [ -f "$bundle/data/dragon-100k.obj" ] && { mesh_scene dragon "$bundle/data/dragon-100k.obj" 0.1 -0.55 4; scenes+=(dragon); }
  # (name, extra options, exact?) — the lecture scenes also with the grid sampler, for identical bytes.
  local cases=("lecture|--sampler grid|exact" "lecture-whitted|--sampler grid|exact" "lecture-distributed|--sampler grid --spp 4|exact"
               "lecture-distributed||rmse" "lecture|--filter mitchell --filter-radius 2 --spp 4 --sampler sobol|rmse")
  for s in bunny dragon; do [[ " ${scenes[*]} " == *" $s "* ]] && cases+=("$s||rmse" "$s|--sampler grid|exact"); done
  # The other structures the GPU traverses.
  cases+=("lecture-whitted|--sampler grid --accel kdtree|exact" "lecture-whitted|--sampler grid --accel octree|exact")
  # Instances: 1,024 placements of groups, each with its own structure.
  cp "$bundle/scenes/instances.yaml" "$out/" && cp -r "$bundle/scenes/meshes" "$out/"
  cases+=("instances|--sampler grid|exact")
  # Motion blur: moving spheres, a turning mesh (an instance of itself), moving solids and spins
  # (about a centre, several turns), whose turns take a sine and a cosine (which may round
  # differently on the device).
  cp "$bundle/scenes/motion-blur.yaml" "$bundle/scenes/motion-solids.yaml" "$bundle/scenes/motion-spin.yaml" "$out/"
  cases+=("motion-blur|--spp 4|rmse" "motion-solids|--spp 4|rmse" "motion-spin|--spp 4|rmse")
  # Nested instances (unfolded into records of one level), moving instances inside groups, and
  # records carried by two motions (a top that precesses, a car's spinning wheels as it turns).
  cp "$bundle/scenes/instances-nested.yaml" "$bundle/scenes/instances-windmills.yaml" "$bundle/scenes/motion-tumble.yaml" "$out/"
  cases+=("instances-nested|--sampler grid|exact" "instances-windmills|--spp 4|rmse" "motion-tumble|--spp 4|rmse")
  # Image textures: planar, spherical and cylindrical (an arc cosine and sine each), and a mesh's
  # own texture coordinates (uv).
  cp "$bundle/scenes/textures.yaml" "$bundle/scenes/uv-mesh.yaml" "$out/" && cp -r "$bundle/scenes/textures" "$out/"
  cases+=("textures|--sampler grid|rmse" "uv-mesh|--sampler grid|rmse")
  # Meshes in their files' materials (per-face materials; a glTF model's embedded picture) under
  # an area light (the Cornell box, OBJ + MTL).
  cp "$bundle/scenes/gltf.yaml" "$bundle/scenes/cornell-box.yaml" "$out/"
  cases+=("gltf|--sampler grid|rmse" "cornell-box|--spp 4|rmse")
  # Path tracing (integrator: path): one path per camera sample, diffuse bounces.
  cp "$bundle/scenes/cornell-box-path.yaml" "$out/"
  cases+=("cornell-box-path|--spp 16|rmse" "lecture-whitted|--integrator path --spp 4|rmse")
  [[ " ${scenes[*]} " == *" bunny "* ]] && cases+=("bunny|--sampler grid --accel kdtree|exact" "bunny|--sampler grid --accel octree|exact")
  local c name opts mode i=0
  for c in "${cases[@]}"; do
    IFS='|' read -r name opts mode <<< "$c"; i=$((i + 1))
    # shellcheck disable=SC2086
    tool strahl "$out/$name.yaml" --width 640 --height 360 $opts --device cpu -o "$out/cpu-$i.pfm" > "$out/cpu-$i.log" 2>&1 \
      || { cat "$out/cpu-$i.log"; echo "FAIL: the CPU render of $name failed"; exit 2; }
    echo "cpu   $name $opts: $(grep -h '^throughput' "$out/cpu-$i.log")"
  done

  # The GPU: where there is none, this is where the check ends.
  local probe
  probe=$(tool strahl --device cuda --width 64 --height 36 -o "$out/probe.pfm" 2>&1); local rc=$?
  echo "$probe" | tail -3
  if [ $rc != 0 ]; then
    echo "FAIL at the GPU (exit $rc): $(grep 'error' <<< "$probe" | head -1)"
    exit 3
  fi

  i=0
  for c in "${cases[@]}"; do
    IFS='|' read -r name opts mode <<< "$c"; i=$((i + 1))
    # shellcheck disable=SC2086
    tool strahl "$out/$name.yaml" --width 640 --height 360 $opts --device cuda -o "$out/gpu-$i.pfm" > "$out/gpu-$i.log" 2>&1 \
      || { cat "$out/gpu-$i.log"; note "FAIL  $name $opts: the GPU render failed"; failures=$((failures + 1)); continue; }
    grep -h '^device' "$out/gpu-$i.log"
    local before=$failures
    compare "$name $opts" "$mode" "$out/cpu-$i.pfm" "$out/gpu-$i.pfm"
    # Only the images of a failed comparison come back (the device tool returns what $OUT holds).
    [ $failures = "$before" ] && rm -f "$out/cpu-$i.pfm" "$out/gpu-$i.pfm"
  done

  # Speed, scene resident: kernel time per frame (CUDA events), median of the frames; the lecture
  # scenes also with each variant of the render kernel ("kernel" lines: registers, occupancy).
  bench "$out/lecture-whitted.yaml" --width 1920 --height 1080 --spp 1 --frames 50 --kernels --viewer 50
  bench "$out/lecture-distributed.yaml" --width 1920 --height 1080 --spp 16 --frames 10 --kernels
  for s in bunny dragon; do
    [[ " ${scenes[*]} " == *" $s "* ]] && bench "$out/$s.yaml" --width 1920 --height 1080 --spp 1 --frames 20 --primary
  done
  python3 "$here/tools/make_bumpy_sphere.py" "$out/bumpy.ply" 709 \
    && mesh_scene bumpy "$out/bumpy.ply" 0.5 0 4 \
    && bench "$out/bumpy.yaml" --width 1920 --height 1080 --spp 1 --frames 20 --primary
  rm -f "$out/bumpy.ply"

  echo
  echo "== gpu-check summary (goals on one H200: lecture-whitted 1080p 1 spp ≥ 200 frames/s; bunny/dragon"
  echo "   primary ≥ 1 Grays/s; 1M triangles ≥ 0.5 Grays/s; distributed 16 spp ≥ 10 frames/s)"
  printf '%s\n' "${table[@]}"
  goals
  [ $failures = 0 ] && echo "all comparisons passed" || echo "$failures comparisons FAILED"
  [ $failures = 0 ]
}

case "${1:-}" in
  prepare) shift; prepare "$@" ;;
  run) run ;;
  goals-of) shift; table=(); while IFS= read -r l; do table+=("$l"); done < "$1"; goals ;;  # a saved table (tests)
  *) sed -n '2,/^set -u/p' "$0" | sed '$d'; exit 1 ;;
esac
