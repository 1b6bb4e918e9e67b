// vibrissa viewer (docs/viewer.md): whiskers and objects in 3D (three.js r111 + OrbitControls), a time slider
// and play button, whiskers coloured by a signal, and the selected whisker's base signals with a cursor.
// The page's data: the JSON of #vibrissa-meta and base64 binary arrays in <script type=
// "application/octet-stream"> elements (python/vibrissa/viewer.py writes both). Positions are in mm.
(async function () {
  "use strict";
  const startedMs = performance.now();
  const meta = JSON.parse(document.getElementById("vibrissa-meta").textContent);
  const DTYPES = { float32: Float32Array, int16: Int16Array, uint8: Uint8Array, uint32: Uint32Array };
  const blobCache = new Map();

  // A binary array of the page (python/vibrissa/viewer.py, _Blobs): base64 -> inflate -> byte planes
  // joined -> typed array -> running sum along the first axis when delta coded. Decoded on first use (a
  // head pitch's arrays only when it is shown) and kept.
  async function blob(id) {
    if (blobCache.has(id)) return blobCache.get(id);
    const el = document.getElementById(id);
    const text = atob(el.textContent.trim());
    let raw = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) raw[i] = text.charCodeAt(i);
    if (el.dataset.encoding === "deflate") {
      const stream = new Blob([raw]).stream().pipeThrough(new DecompressionStream("deflate"));
      raw = new Uint8Array(await new Response(stream).arrayBuffer());
    }
    const T = DTYPES[el.dataset.dtype], size = T.BYTES_PER_ELEMENT, n = raw.length / size;
    const bytes = new Uint8Array(raw.length);
    for (let b = 0; b < size; b++) {
      const plane = raw.subarray(b * n, (b + 1) * n);
      for (let i = 0; i < n; i++) bytes[i * size + b] = plane[i];
    }
    const arr = new T(bytes.buffer);
    const stride = +(el.dataset.delta || 0);
    if (stride) for (let i = stride; i < n; i++) arr[i] += arr[i - stride];  // Int16Array: wraps as numpy did
    blobCache.set(id, arr);
    return arr;
  }

  const nW = meta.whiskers.length, nT = meta.times.length, K = meta.nodes, nS = meta.signals.length;
  // The slider's axis: time by default; a sweep of solves steps through the values of its last parameter.
  const axis = meta.frame_axis || { label: "t", unit: "ms", scale: 1e3 };
  const axisText = (t, digits) => `${(meta.times[t] * axis.scale).toFixed(digits)}${axis.unit ? " " + axis.unit : ""}`;
  const STATE_COLOURS = ["#9a9a9a", "#D55E00", "#0072B2"];  // free, contact, pushed past (figures/style.py)
  // cividis-like sequential map (dark blue -> yellow), monotonic in lightness.
  const CMAP = [[0.0, 0x00, 0x22, 0x4e], [0.25, 0x3b, 0x49, 0x6c], [0.5, 0x7c, 0x7b, 0x78], [0.75, 0xbc, 0xaf, 0x6f],
                [1.0, 0xfe, 0xe8, 0x38]];
  function cmap(x, out) {
    x = Math.min(1, Math.max(0, x));
    let k = 0;
    while (k < CMAP.length - 2 && x > CMAP[k + 1][0]) k++;
    const a = CMAP[k], b = CMAP[k + 1], f = (x - a[0]) / (b[0] - a[0]);
    out.setRGB((a[1] + f * (b[1] - a[1])) / 255, (a[2] + f * (b[2] - a[2])) / 255, (a[3] + f * (b[3] - a[3])) / 255);
    return out;
  }

  // ---- scene ---------------------------------------------------------------------------------------------
  const host = document.getElementById("scene");
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xffffff, 1);
  host.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(35, 1, 0.1, 5000);
  camera.up.set(0, 0, 1);  // world z is dorsal
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.addEventListener("change", () => { updateRibbons(); render(); });
  scene.add(new THREE.AxesHelper(5));  // world axes at the origin: x red, y green, z blue, 5 mm

  const state = { group: 0, frame: 0, selected: meta.initial_whisker || 0, colour: 0, playing: false };
  const whiskerMeshes = [], whiskerPositions = [];
  const widthMm = meta.ribbon_width_mm;  // drawn width at the base; tapers to a third at the tip
  for (let w = 0; w < nW; w++) {
    const g = new THREE.BufferGeometry();
    const pos = new Float32Array(K * 2 * 3);
    g.setAttribute("position", new THREE.BufferAttribute(pos, 3));
    const index = [];
    for (let k = 0; k + 1 < K; k++) index.push(2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 1, 2 * k + 3, 2 * k + 2);
    g.setIndex(index);
    const m = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: 0x888888, side: THREE.DoubleSide }));
    m.userData.whisker = w;
    m.frustumCulled = false;
    scene.add(m);
    whiskerMeshes.push(m);
    whiskerPositions.push(new Float32Array(K * 3));  // the centre line of the shown frame [mm]
  }
  const baseDots = new THREE.Points(new THREE.BufferGeometry(),
                                    new THREE.PointsMaterial({ color: 0x444444, size: 4, sizeAttenuation: false }));
  baseDots.geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(nW * 3), 3));
  baseDots.frustumCulled = false;
  scene.add(baseDots);
  const contactDots = new THREE.Points(new THREE.BufferGeometry(),
                                       new THREE.PointsMaterial({ color: 0x000000, size: 7, sizeAttenuation: false }));
  contactDots.geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(nW * 3), 3));
  contactDots.frustumCulled = false;
  scene.add(contactDots);
  // Rest shapes (a solve: the undeflected whisker) as thin grey lines, per group.
  const restLines = [];
  if (meta.rest) for (let w = 0; w < nW; w++) {
    const l = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineDashedMaterial({ color: 0x777777, dashSize: 0.4, gapSize: 0.3 }));
    l.geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(K * 3), 3));
    l.frustumCulled = false;
    scene.add(l);
    restLines.push(l);
  }
  // Arrows (a solve: the contact force at the contact point, the force and moment at the base): per group a
  // blob [arrow][frame][6] of origin and drawn vector [mm]; their lengths are scaled, the values are in the table.
  const arrows = (meta.arrows || []).map((a) => {
    const h = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, new THREE.Color(a.colour).getHex());
    h.frustumCulled = false;
    scene.add(h);
    return h;
  });
  const selectedLine = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x000000 }));
  selectedLine.geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(K * 3), 3));
  selectedLine.frustumCulled = false;
  scene.add(selectedLine);

  // Objects: straight edges as thick black segments (per frame), surfaces as translucent meshes placed by
  // their pose R_WO (row by row) and p_WO at each frame.
  const edgeMeshes = [];
  for (let e = 0; e < meta.edges; e++) {
    const m = new THREE.Mesh(new THREE.CylinderBufferGeometry(meta.edge_radius_mm, meta.edge_radius_mm, 1, 12),
                             new THREE.MeshBasicMaterial({ color: 0x222222 }));
    m.frustumCulled = false;
    scene.add(m);
    edgeMeshes.push(m);
  }
  const objectMeshes = [];
  for (const o of meta.objects) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(await blob(o.vertices), 3));
    g.setIndex(new THREE.BufferAttribute(await blob(o.triangles), 1));
    const m = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: 0x555555, transparent: true, opacity: 0.25,
                                                              side: THREE.DoubleSide, depthWrite: false }));
    const wire = new THREE.LineSegments(new THREE.EdgesGeometry(g, 20), new THREE.LineBasicMaterial({ color: 0x333333 }));
    m.add(wire);
    m.matrixAutoUpdate = false;
    m.frustumCulled = false;
    scene.add(m);
    objectMeshes.push(m);
  }

  // ---- data of the shown group (head pitch) --------------------------------------------------------------
  async function groupData() {
    const g = meta.groups[state.group];
    const [shapes, st, signals, contact, edges, poses, rest, arrowData] = await Promise.all([
      blob(g.shapes), blob(g.state), blob(g.signals), blob(g.contact), meta.edges ? blob(g.edges) : null,
      meta.objects.length ? blob(g.object_poses) : null, g.rest ? blob(g.rest) : null,
      g.arrows ? blob(g.arrows) : null]);
    restLines.forEach((l, w) => {
      l.geometry.attributes.position.array.set(rest.subarray(w * K * 3, (w + 1) * K * 3));
      l.geometry.attributes.position.needsUpdate = true;
      l.computeLineDistances();
    });
    return { shapes, state: st, signals, contact, edges, poses, ranges: g.ranges, arrows: arrowData, table: g.table };
  }
  let data = await groupData();

  function signalAt(s, w, t) { return data.signals[(s * nW + w) * nT + t]; }

  const tmpColour = new THREE.Color();
  function whiskerColour(w, t) {
    const c = meta.colour_by[state.colour];
    if (c.kind === "state") return tmpColour.set(STATE_COLOURS[data.state[w * nT + t]] || "#9a9a9a");
    const v = signalAt(c.signal, w, t), r = data.ranges[c.signal];
    if (!Number.isFinite(v) || data.state[w * nT + t] !== 1) return tmpColour.set("#c8c8c8");  // not in contact: grey
    const x = c.abs ? Math.abs(v) / (r[2] || 1) : (v - r[0]) / ((r[1] - r[0]) || 1);
    return cmap(x, tmpColour);
  }

  // Centre lines of frame t from the quantised shapes: p = offset + q * step [mm].
  function loadFrame(t) {
    const q = meta.quant, base = baseDots.geometry.attributes.position.array;
    const cp = contactDots.geometry.attributes.position.array;
    let nContact = 0;
    for (let w = 0; w < nW; w++) {
      const p = whiskerPositions[w], o = ((t * nW) + w) * K * 3;
      for (let i = 0; i < K * 3; i++) p[i] = q.offset[i % 3] + data.shapes[o + i] * q.step[i % 3];
      base.set(p.subarray(0, 3), w * 3);
      whiskerMeshes[w].material.color.copy(whiskerColour(w, t));
      if (data.state[w * nT + t] === 1) {
        const c = (w * nT + t) * 3;
        if (Number.isFinite(data.contact[c])) { cp.set(data.contact.subarray(c, c + 3), nContact * 3); nContact++; }
      }
    }
    contactDots.geometry.setDrawRange(0, nContact);
    contactDots.geometry.attributes.position.needsUpdate = true;
    baseDots.geometry.attributes.position.needsUpdate = true;
    const sel = selectedLine.geometry.attributes.position;
    sel.array.set(whiskerPositions[state.selected]);
    sel.needsUpdate = true;
    for (let e = 0; e < edgeMeshes.length; e++) {
      const o = (t * meta.edges + e) * 6, a = new THREE.Vector3().fromArray(data.edges, o),
            b = new THREE.Vector3().fromArray(data.edges, o + 3);
      const m = edgeMeshes[e], d = b.clone().sub(a), len = d.length();
      m.position.copy(a).add(b).multiplyScalar(0.5);
      m.scale.set(1, Math.max(len, 1e-6), 1);
      m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.normalize());
    }
    arrows.forEach((h, a) => {
      const o = (a * nT + t) * 6, v = new THREE.Vector3().fromArray(data.arrows, o + 3), len = v.length();
      h.visible = Number.isFinite(len) && len > 1e-9;
      if (!h.visible) return;
      h.position.fromArray(data.arrows, o);
      h.setDirection(v.normalize());
      h.setLength(len, 0.25 * len, 0.12 * len);
    });
    objectMeshes.forEach((m, i) => {
      const p = data.poses.subarray((t * objectMeshes.length + i) * 12, (t * objectMeshes.length + i + 1) * 12);
      m.matrix.set(p[0], p[1], p[2], p[9], p[3], p[4], p[5], p[10], p[6], p[7], p[8], p[11], 0, 0, 0, 1);
      m.matrixWorldNeedsUpdate = true;
    });
    updateRibbons();
  }

  // Whiskers as ribbons facing the camera, so they keep a visible width (WebGL lines are one pixel wide).
  const va = new THREE.Vector3(), vb = new THREE.Vector3(), vn = new THREE.Vector3(), eye = new THREE.Vector3();
  function updateRibbons() {
    for (let w = 0; w < nW; w++) {
      const p = whiskerPositions[w], out = whiskerMeshes[w].geometry.attributes.position;
      for (let k = 0; k < K; k++) {
        const k0 = Math.max(0, k - 1), k1 = Math.min(K - 1, k + 1);
        va.fromArray(p, k0 * 3); vb.fromArray(p, k1 * 3).sub(va);  // tangent
        eye.fromArray(p, k * 3).sub(camera.position);
        vn.crossVectors(vb, eye).normalize();
        if (!Number.isFinite(vn.x)) vn.set(0, 0, 0);
        const half = 0.5 * widthMm * (1 - (2 / 3) * k / (K - 1));
        for (let c = 0; c < 3; c++) {
          out.array[(2 * k) * 3 + c] = p[k * 3 + c] + half * vn.getComponent(c);
          out.array[(2 * k + 1) * 3 + c] = p[k * 3 + c] - half * vn.getComponent(c);
        }
      }
      out.needsUpdate = true;
      whiskerMeshes[w].geometry.computeBoundingSphere();
    }
  }

  // ---- camera --------------------------------------------------------------------------------------------
  function frameCamera() {
    const c = new THREE.Vector3().fromArray(meta.view.centre), r = meta.view.radius;
    controls.target.copy(c);
    const d = new THREE.Vector3().fromArray(meta.view.direction).normalize();
    camera.position.copy(c).addScaledVector(d, r / Math.tan((camera.fov * Math.PI) / 360) * 0.8);
    camera.near = r / 100; camera.far = r * 100;
    camera.updateProjectionMatrix();
    controls.update();
  }
  function resize() {
    const w = host.clientWidth, h = host.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
    drawPlots();
    render();
  }
  function render() { renderer.render(scene, camera); }

  // ---- plots of the selected whisker ----------------------------------------------------------------------
  const plotsEl = document.getElementById("plots"), info = document.getElementById("info");
  const plotCanvases = meta.signals.map((s, i) => {
    const c = document.createElement("canvas");
    c.className = "plot"; c.id = "plot-" + s.key; c.dataset.signal = i;
    c.addEventListener("click", (ev) => {  // click a plot: go to that time
      const r = c.getBoundingClientRect(), m = PLOT_MARGINS;
      const x = (ev.clientX - r.left - m.l) / (r.width - m.l - m.r);
      setFrame(Math.round(Math.min(1, Math.max(0, x)) * (nT - 1)));
    });
    plotsEl.appendChild(c);
    return c;
  });
  const PLOT_MARGINS = { l: 52, r: 8, t: 18, b: 18 };  // CSS pixels around each plot
  function drawPlots() {
    const w = state.selected, t0 = meta.times[0], t1 = meta.times[nT - 1];
    plotCanvases.forEach((c, s) => {
      const dpr = window.devicePixelRatio || 1, W = c.clientWidth, H = c.clientHeight;
      if (c.width !== Math.round(W * dpr)) { c.width = Math.round(W * dpr); c.height = Math.round(H * dpr); }
      const g = c.getContext("2d");
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.clearRect(0, 0, W, H);
      const m = PLOT_MARGINS, pw = W - m.l - m.r, ph = H - m.t - m.b;
      let lo = Infinity, hi = -Infinity;
      for (let t = 0; t < nT; t++) { const v = signalAt(s, w, t); if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } }
      if (!(hi >= lo)) { lo = 0; hi = 1; }
      if (hi - lo < 1e-12) { lo -= 0.5; hi += 0.5; }
      const pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
      const X = (t) => m.l + (pw * (meta.times[t] - t0)) / ((t1 - t0) || 1), Y = (v) => m.t + ph * (1 - (v - lo) / (hi - lo));
      g.strokeStyle = "#999"; g.lineWidth = 1; g.strokeRect(m.l, m.t, pw, ph);
      g.fillStyle = "#222"; g.font = "11px system-ui, sans-serif";
      const sig = meta.signals[s], v = signalAt(s, w, state.frame);
      g.fillText(`${sig.label} [${sig.unit}]: ${Number.isFinite(v) ? v.toPrecision(4) : "—"}`, m.l, 12);
      g.textAlign = "right";
      g.fillText(hi.toPrecision(3), m.l - 3, m.t + 9); g.fillText(lo.toPrecision(3), m.l - 3, m.t + ph);
      g.textAlign = "left";
      g.fillText(axisText(0, axis.digits === undefined ? 0 : axis.digits), m.l, H - 4);
      if (meta.frame_axis) { g.textAlign = "center"; g.fillText(axis.label, m.l + pw / 2, H - 4); }  // not time: name it
      g.textAlign = "right"; g.fillText(axisText(nT - 1, axis.digits === undefined ? 0 : axis.digits), m.l + pw, H - 4);
      g.textAlign = "left";
      g.strokeStyle = "#0072B2"; g.lineWidth = 1.5; g.beginPath();
      let pen = false;
      for (let t = 0; t < nT; t++) {
        const y = signalAt(s, w, t);
        if (!Number.isFinite(y)) { pen = false; continue; }
        if (pen) g.lineTo(X(t), Y(y)); else g.moveTo(X(t), Y(y));
        pen = true;
      }
      g.stroke();
      g.strokeStyle = "#D55E00"; g.lineWidth = 1; g.beginPath();  // cursor at the shown frame
      g.moveTo(X(state.frame), m.t); g.lineTo(X(state.frame), m.t + ph); g.stroke();
    });
    const st = meta.state_names[data.state[w * nT + state.frame]];
    info.textContent = `${meta.whisker_label} ${meta.whiskers[w]} (${st}) — ${meta.title}`;
    if (data.table) {  // a solve: its numbers (the group's, or the shown frame's when they change with it)
      const rows = data.table.length === nT && Array.isArray(data.table[0][0]) ? data.table[state.frame] : data.table;
      const tbl = document.createElement("table");
      tbl.id = "values";
      for (const [k, v] of rows) {
        const tr = tbl.insertRow();
        tr.insertCell().textContent = k;
        tr.insertCell().textContent = v;
      }
      info.appendChild(tbl);
    }
  }

  // ---- controls ------------------------------------------------------------------------------------------
  const slider = document.getElementById("slider"), timeEl = document.getElementById("time");
  const pitchSel = document.getElementById("pitch"), colourSel = document.getElementById("colour");
  const whiskerSel = document.getElementById("whisker"), playBtn = document.getElementById("play");
  slider.max = String(nT - 1);
  // The groups (head pitches; a sweep's runs) are a grid: one list per dimension, the group index their
  // C-order ravel. Without meta.group_dims, one list of the groups' labels.
  const dims = meta.group_dims || [{ label: meta.group_label, values: meta.groups.map((g) => g.label) }];
  const dimSels = dims.map((d, i) => {
    const sel = i === 0 ? pitchSel : document.createElement("select");
    sel.dataset.dim = String(i);
    sel.id = i === 0 ? "pitch" : `dim-${i}`;
    d.values.forEach((v, j) => sel.add(new Option(v, String(j))));
    if (i === 0) {
      document.getElementById("pitch-box").firstChild.textContent = d.label + " ";
      if (d.values.length < 2 && dims.length === 1) document.getElementById("pitch-box").style.display = "none";
    } else {
      const label = document.createElement("label");
      label.className = "dim-box";
      label.append(d.label + " ", sel);
      document.getElementById("pitch-box").after(label);
    }
    return sel;
  });
  // keep the lists' order in the bar: dimension 0 first
  for (let i = dimSels.length - 1; i > 0; i--) document.getElementById("pitch-box").after(dimSels[i].parentElement);
  function groupOfSelects() { return dimSels.reduce((g, s, i) => g * dims[i].values.length + +s.value, 0); }
  function selectsOfGroup(g) {
    for (let i = dims.length - 1; i >= 0; i--) { dimSels[i].value = String(g % dims[i].values.length); g = Math.floor(g / dims[i].values.length); }
  }
  if (nT < 2) {  // one frame (a single solve): no slider, no play, no plots over time
    for (const id of ["play", "slider", "time"]) document.getElementById(id).style.display = "none";
    document.getElementById("plots").style.display = "none";
  }
  meta.colour_by.forEach((c, i) => colourSel.add(new Option(c.label, String(i))));
  meta.whiskers.forEach((n, i) => whiskerSel.add(new Option(n, String(i))));
  whiskerSel.value = String(state.selected);
  if (nW < 2) whiskerSel.parentElement.style.display = "none";
  if (meta.arrows && meta.arrows.length) {  // the arrows' key, under the colour scale
    const key = document.createElement("div");
    key.id = "arrow-key";
    for (const a of meta.arrows) {
      const row = document.createElement("div"), mark = document.createElement("span");
      mark.textContent = "\u2192 "; mark.style.color = a.colour; mark.style.fontWeight = "bold";
      row.append(mark, a.label);
      key.appendChild(row);
    }
    const note = document.createElement("div");
    note.textContent = "arrows: direction; length scaled (values in the table)";
    note.style.color = "#666";
    key.appendChild(note);
    document.getElementById("legend").appendChild(key);
  }

  function updateLegend() {
    const c = meta.colour_by[state.colour], bar = document.getElementById("legend-bar"), g = bar.getContext("2d");
    document.getElementById("legend-title").textContent = c.label + " ";
    if (c.kind === "state") {
      const n = meta.state_names.length;
      meta.state_names.forEach((_, i) => { g.fillStyle = STATE_COLOURS[i]; g.fillRect((i * bar.width) / n, 0, bar.width / n, bar.height); });
      document.getElementById("legend-range").textContent = " " + meta.state_names.join(" | ");
      return;
    }
    const col = new THREE.Color();
    for (let x = 0; x < bar.width; x++) { g.fillStyle = "#" + cmap(x / (bar.width - 1), col).getHexString(); g.fillRect(x, 0, 1, bar.height); }
    const r = data.ranges[c.signal], unit = meta.signals[c.signal].unit;
    document.getElementById("legend-range").textContent = c.abs ? ` 0 … ${r[2].toPrecision(3)} ${unit}`
                                                                : ` ${r[0].toPrecision(3)} … ${r[1].toPrecision(3)} ${unit}`;
  }

  function setFrame(t) {
    state.frame = Math.max(0, Math.min(nT - 1, t | 0));
    slider.value = String(state.frame);
    timeEl.textContent = `${axis.label} = ${axisText(state.frame, axis.digits === undefined ? 1 : axis.digits)} (frame ${state.frame + 1}/${nT})`;
    loadFrame(state.frame);
    drawPlots();
    render();
  }
  function select(w) {
    state.selected = w;
    whiskerSel.value = String(w);
    setFrame(state.frame);
  }
  async function setGroup(i) {
    state.group = i; selectsOfGroup(i);
    data = await groupData();
    updateLegend(); setFrame(state.frame);
  }
  slider.addEventListener("input", () => setFrame(+slider.value));
  dimSels.forEach((s) => s.addEventListener("change", () => setGroup(groupOfSelects())));
  colourSel.addEventListener("change", () => { state.colour = +colourSel.value; updateLegend(); setFrame(state.frame); });
  whiskerSel.addEventListener("change", () => select(+whiskerSel.value));
  let last = 0;
  function tick(now) {
    if (!state.playing) return;
    if (now - last > 1000 / meta.play_fps) { last = now; setFrame((state.frame + 1) % nT); }
    requestAnimationFrame(tick);
  }
  playBtn.addEventListener("click", () => {
    state.playing = !state.playing;
    playBtn.innerHTML = state.playing ? "&#10074;&#10074; pause" : "&#9654; play";
    if (state.playing) requestAnimationFrame(tick);
  });

  // Click a whisker to select it (a click, not the end of an orbit drag).
  const raycaster = new THREE.Raycaster(), mouse = new THREE.Vector2();
  let down = null;
  renderer.domElement.addEventListener("pointerdown", (e) => { down = [e.clientX, e.clientY]; });
  renderer.domElement.addEventListener("pointerup", (e) => {
    if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
    const r = renderer.domElement.getBoundingClientRect();
    mouse.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    raycaster.setFromCamera(mouse, camera);
    const hit = raycaster.intersectObjects(whiskerMeshes, false)[0];
    if (hit) select(hit.object.userData.whisker);
  });

  window.addEventListener("resize", resize);
  frameCamera();
  selectsOfGroup(0);
  updateLegend();
  setFrame(meta.initial_frame || 0);
  resize();
  // For tests and scripting: the state, and where a whisker node is on the screen (CSS pixels in the page).
  window.vibrissaViewer = {
    meta, setFrame, select, setGroup,
    get frame() { return state.frame; }, get selected() { return state.selected; }, get group() { return state.group; },
    nodeOnScreen(w, k) {
      const v = new THREE.Vector3().fromArray(whiskerPositions[w], k * 3).project(camera);
      const r = renderer.domElement.getBoundingClientRect();
      return [r.left + ((v.x + 1) / 2) * r.width, r.top + ((1 - v.y) / 2) * r.height];
    },
    projectMm(p) {
      const v = new THREE.Vector3().fromArray(p).project(camera);
      const r = renderer.domElement.getBoundingClientRect();
      return [r.left + ((v.x + 1) / 2) * r.width, r.top + ((1 - v.y) / 2) * r.height];
    },
    centreLine(w) { return Array.from(whiskerPositions[w]); },
    signal(s, w, t) { return signalAt(s, w, t); },
    arrow(a) { const h = arrows[a]; return h.visible ? { origin: h.position.toArray(), direction: new THREE.Vector3(0, 1, 0).applyQuaternion(h.quaternion).toArray() } : null; },
    screenNodes() {
      const out = [];
      for (let w = 0; w < nW; w++) { const line = []; for (let k = 0; k < K; k++) line.push(this.nodeOnScreen(w, k)); out.push(line); }
      return out;
    },
    ready: true,
    openedMs: performance.now(),  // from navigation start to a drawn first frame
    startedMs,  // when this script started (the page parsed, three.js loaded)
  };
  document.title = meta.title;
})();
