// The 3-D viewer gplan writes into one self-contained HTML file (`gplan plan --html`):
// the obstacles as checked, the robot's links posed at every frame of the path (poses
// computed by gplan's forward kinematics, read here, never recomputed), an animation
// with play/pause and a slider, the start and the goal as ghosts, orbit and zoom.
//
// The data is the JSON in <script type="application/json" id="gplan-data">:
//   name, summary: text (shown with textContent only: input names never become markup)
//   meshes: [{positions: [x y z ...], indices: [i j k ...]}]
//   obstacles: [{name, mesh}]                 in the scene frame
//   links: [{name, mesh}]                     in the link frame
//   frames: [[12 numbers per link: the 3x3 rotation by columns, then the translation]]
//   waypoints: [frame index of each waypoint]
//   roadmap (on request): {milestones, points: [x y z ...], valid: [i j ...], unknown: [i j ...]}
//   rows (gplan check --html): per frame {label, link, obstacle, other_link}: configurations
//     shown one at a time, what collides there drawn red
//   notice: text, or ""
// URL parameters: ?t=0..1 shows that point of the path, paused (for tests and links).
// Where the page is drawn, document.body gets data-status="drawn"; an error sets
// data-status="error: ..." (tests read it from the DOM).

import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

function fail(error) {
  document.body.dataset.status = "error: " + (error && error.message ? error.message : error);
}
window.addEventListener("error", (event) => fail(event.error || event.message));

function geometryOf(mesh) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(mesh.positions, 3));
  geometry.setIndex(mesh.indices);
  geometry.computeVertexNormals();
  return geometry;
}

function setPose(object, pose) {
  const m = new THREE.Matrix4();
  m.set(pose[0], pose[3], pose[6], pose[9],
        pose[1], pose[4], pose[7], pose[10],
        pose[2], pose[5], pose[8], pose[11],
        0, 0, 0, 1);
  object.matrixAutoUpdate = false;
  object.matrix.copy(m);
  object.matrixWorldNeedsUpdate = true;
}

// A group of the robot's links with one material, posed at `frame`.
function robotAt(data, geometries, material, frame) {
  const group = new THREE.Group();
  data.links.forEach((link, l) => {
    if (link.mesh < 0) return;
    const mesh = new THREE.Mesh(geometries[link.mesh], material);
    setPose(mesh, data.frames[frame].slice(12 * l, 12 * l + 12));
    group.add(mesh);
  });
  return group;
}

function element(tag, parent, text) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  parent.appendChild(e);
  return e;
}

function main() {
  const data = JSON.parse(document.getElementById("gplan-data").textContent);
  const params = new URLSearchParams(window.location.search);

  const panel = element("div", document.body);
  panel.id = "panel";
  element("div", panel, data.name).className = "title";
  element("div", panel, data.summary);
  if (data.notice) element("div", panel, data.notice).className = "notice";
  const controls = element("div", panel);
  const play = element("button", controls, "Pause");
  const slider = element("input", controls);
  slider.type = "range";
  slider.min = 0;
  slider.max = Math.max(0, data.frames.length - 1);
  slider.value = 0;
  const label = element("span", controls);
  const legend = element("div", panel, "green: start, red: goal; drag to orbit, wheel to zoom");
  legend.className = "legend";

  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(0xf4f4f4);
  document.body.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 2, 3);
  scene.add(sun);

  const geometries = data.meshes.map(geometryOf);
  const obstacleMaterial = new THREE.MeshStandardMaterial({
    color: 0x9aa0a6, roughness: 0.9, transparent: true, opacity: 0.55, side: THREE.DoubleSide,
    depthWrite: false,
  });
  const obstacles = data.obstacles.map((obstacle) => {
    const mesh = new THREE.Mesh(geometries[obstacle.mesh], obstacleMaterial);
    scene.add(mesh);
    return mesh;
  });
  const hitMaterial = new THREE.MeshStandardMaterial({ color: 0xe02020, roughness: 0.6 });
  const hitObstacleMaterial = new THREE.MeshStandardMaterial({
    color: 0xe02020, transparent: true, opacity: 0.6, side: THREE.DoubleSide, depthWrite: false,
  });

  const last = data.frames.length - 1;
  const ghost = (color) => new THREE.MeshStandardMaterial({
    color, transparent: true, opacity: 0.3, depthWrite: false, side: THREE.DoubleSide,
  });
  const rows = data.rows || null;
  if (!rows) {  // a path: its start and goal
    scene.add(robotAt(data, geometries, ghost(0x22aa44), 0));
    scene.add(robotAt(data, geometries, ghost(0xdd3333), last));
  } else {
    legend.textContent = "red: what collides; drag to orbit, wheel to zoom";
  }
  const robotMaterial = new THREE.MeshStandardMaterial({ color: 0x3366cc, roughness: 0.5, metalness: 0.1 });
  const robot = robotAt(data, geometries, robotMaterial, 0);
  scene.add(robot);

  // The root's way along the path.
  const way = [];
  for (const frame of data.frames) way.push(new THREE.Vector3(frame[9], frame[10], frame[11]));
  if (way.length > 1 && !rows) {
    scene.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(way),
                             new THREE.LineBasicMaterial({ color: 0xcc6600 })));
  }

  // The roadmap, on request: milestones as points, valid edges green, unknown grey;
  // shown or hidden with a box.
  if (data.roadmap) {
    const roadmap = new THREE.Group();
    const points = new THREE.Float32BufferAttribute(data.roadmap.points, 3);
    const cloud = new THREE.BufferGeometry();
    cloud.setAttribute("position", points);
    roadmap.add(new THREE.Points(cloud, new THREE.PointsMaterial({ color: 0x333333, size: 3, sizeAttenuation: false })));
    for (const [edges, color, opacity] of [[data.roadmap.unknown, 0xbbbbbb, 0.15],
                                           [data.roadmap.valid, 0x22aa44, 0.8]]) {
      const lines = new THREE.BufferGeometry();
      lines.setAttribute("position", points);
      lines.setIndex(edges);
      roadmap.add(new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color, transparent: true, opacity })));
    }
    scene.add(roadmap);
    const toggle = element("label", panel);
    const box = element("input", toggle);
    box.type = "checkbox";
    box.checked = true;
    box.onchange = () => { roadmap.visible = box.checked; };
    toggle.appendChild(document.createTextNode(
      " roadmap: " + data.roadmap.milestones + " milestones (" + data.roadmap.points.length / 3 + " drawn)"));
  }

  // The camera: all of it in view, from above and aside, z up.
  const box = new THREE.Box3().setFromObject(scene);
  const centre = box.getCenter(new THREE.Vector3());
  const size = Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3);
  const camera = new THREE.PerspectiveCamera(45, window.innerWidth / window.innerHeight, size / 1000, size * 20);
  camera.up.set(0, 0, 1);
  camera.position.copy(centre).add(new THREE.Vector3(0.6, -0.9, 0.7).multiplyScalar(size));
  const orbit = new OrbitControls(camera, renderer.domElement);
  orbit.target.copy(centre);
  orbit.update();

  const show = (frame) => {
    frame = Math.min(last, Math.max(0, Math.round(frame)));
    const row = rows ? rows[frame] : null;
    robot.children.forEach((mesh, i) => {
      const l = robot.userData.links[i];
      setPose(mesh, data.frames[frame].slice(12 * l, 12 * l + 12));
      mesh.material = row && (l === row.link || l === row.other_link) ? hitMaterial : robotMaterial;
    });
    obstacles.forEach((mesh, o) => {
      mesh.material = row && o === row.obstacle ? hitObstacleMaterial : obstacleMaterial;
    });
    slider.value = frame;
    if (row) {
      label.textContent = " " + (frame + 1) + " of " + rows.length + ": " + row.label;
    } else {
      const waypoint = data.waypoints.filter((f) => f <= frame).length;
      label.textContent = " waypoint " + waypoint + " of " + data.waypoints.length;
    }
  };
  robot.userData.links = data.links.map((link, l) => (link.mesh < 0 ? -1 : l)).filter((l) => l >= 0);

  let playing = !params.has("t") && !rows;
  let position = params.has("t") ? Number(params.get("t")) * last : 0;
  if (!Number.isFinite(position)) position = 0;
  play.textContent = playing ? "Pause" : "Play";
  play.onclick = () => {
    playing = !playing;
    play.textContent = playing ? "Pause" : "Play";
  };
  slider.oninput = () => {
    playing = false;
    play.textContent = "Play";
    position = Number(slider.value);
  };
  window.addEventListener("resize", () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
  });

  const framesPerSecond = Math.max(1, last / 8);  // the whole path in about 8 s
  let before = performance.now();
  const draw = (now) => {
    if (playing) {
      position += ((now - before) / 1000) * framesPerSecond;
      if (position > last) position = 0;
    }
    before = now;
    show(position);
    renderer.render(scene, camera);
    document.body.dataset.status = "drawn";
    requestAnimationFrame(draw);
  };
  show(position);
  renderer.render(scene, camera);
  document.body.dataset.status = "drawn";
  requestAnimationFrame(draw);
}

try {
  main();
} catch (error) {
  fail(error);
}
