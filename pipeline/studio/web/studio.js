// fabmesh studio: the page. It talks to the server's JSON API (docs/studio.md)
// only, with the session's token in the X-Fabmesh-Token header.

const token = document.querySelector('meta[name="fabmesh-token"]').content;
const $ = (id) => document.getElementById(id);

// What the page shows and what the tests read (window.fabmeshStudio).
const state = {
  design: null,        // GET /api/design
  overrides: {},       // name or key path -> value, sent with every build
  lastChanged: null,   // the field last moved: where an error without a field is pinned
  builds: 0,           // builds answered (valid or not)
  validBuilds: 0,
  errors: 0,
  mesh: null,          // the URL of the mesh shown
  meshSignature: '',   // a digest of the shown mesh's positions
  plotSvg: '',
  version: null,
  syncParameters: false,  // a parameter set was picked: the next valid build's values go into the fields
  settledChange: 0,       // the newest change whose proven build is answered and shown (or its error)
  lastReport: null,       // the last valid build's report (run --json's item)
  undoDepth: 0,           // changes that undo can take back, and redo bring again
  redoDepth: 0,
  error: null,         // the last build's error object, or null
  controlPoints: [],   // the shown answer's control_points: the points listed under Points
  // The last valid build's times in the page, ms from the request (the bench
  // reads them, bench/studio_latency.mjs): answer (the JSON in), plot, report,
  // mesh (fetched and parsed), shown (in the scene, drawn).
  timings: null,
};
window.fabmeshStudio = state;

async function api(method, path, body) {
  const response = await fetch(path, {
    method,
    headers: {'X-Fabmesh-Token': token, 'Content-Type': 'application/json'},
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  let json = null;
  try {
    json = await response.json();
  } catch (e) {
    json = {error: {message: `HTTP ${response.status}`}};
  }
  return {status: response.status, json};
}

function setStatus(text) { $('status').textContent = text; }

// --- controls ---

function fieldId(name) { return 'field-' + name.replace(/[^A-Za-z0-9_]/g, '_'); }

function addControl(parent, {name, label, value, min, max, step, description, exclusiveMin}) {
  const box = document.createElement('div');
  box.className = 'control';
  box.id = fieldId(name);
  box.dataset.name = name;
  const title = document.createElement('label');
  title.textContent = label;
  box.append(title);
  const row = document.createElement('div');
  row.className = 'row';
  const slider = document.createElement('input');
  slider.type = 'range';
  const number = document.createElement('input');
  number.type = 'number';
  const lo = min ?? Math.min(0, value * 2);
  const hi = max ?? Math.max(1, value * 2);
  const st = step ?? (hi - lo) / 100;
  for (const input of [slider, number]) {
    input.min = exclusiveMin ? lo + st : lo;
    input.max = hi;
    input.step = st;
    input.value = value;
    input.setAttribute('aria-label', label);
  }
  number.min = '';  // the number field may take any value: the design judges it
  number.max = '';
  const changed = (source, other) => {
    other.value = source.value;
    const v = Number(source.value);
    if (source.value === '' || !Number.isFinite(v)) return;
    remember(name);
    state.overrides[name] = v;
    state.lastChanged = name;
    requestBuild();
  };
  slider.addEventListener('input', () => changed(slider, number));
  // A slider's drag is one change for undo: it ends when the slider is let go.
  slider.addEventListener('change', () => { history.gesture = null; });
  number.addEventListener('change', () => {
    changed(number, slider);
    history.gesture = null;
  });
  row.append(slider, number);
  box.append(row);
  if (description) {
    const d = document.createElement('div');
    d.className = 'description';
    d.textContent = description;
    box.append(d);
  }
  const err = document.createElement('div');
  err.className = 'field-error';
  box.append(err);
  parent.append(box);
}

// A choice's select or a switch's checkbox: the value is sent as the text
// (a choice) or true / false (a switch).
function addChoiceControl(parent, p) {
  const box = document.createElement('div');
  box.className = 'control';
  box.id = fieldId(p.name);
  box.dataset.name = p.name;
  const title = document.createElement('label');
  title.textContent = p.name;
  box.append(title);
  let input;
  if (p.kind === 'choice') {
    input = document.createElement('select');
    for (const c of p.choices) {
      const option = document.createElement('option');
      option.value = c;
      option.textContent = c;
      input.append(option);
    }
    input.value = p.text;
  } else {
    input = document.createElement('input');
    input.type = 'checkbox';
    input.checked = p.text === 'true';
  }
  input.setAttribute('aria-label', p.name);
  input.addEventListener('change', () => {
    remember();
    state.overrides[p.name] = p.kind === 'choice' ? input.value : input.checked;
    state.lastChanged = p.name;
    requestBuild();
  });
  box.append(input);
  if (p.description) {
    const d = document.createElement('div');
    d.className = 'description';
    d.textContent = p.description;
    box.append(d);
  }
  const err = document.createElement('div');
  err.className = 'field-error';
  box.append(err);
  parent.append(box);
}

function showControls(design) {
  $('design-name').textContent = design.name;
  $('design-kind').textContent = `${design.kind}, ${design.units}`;
  document.title = `${design.name} - fabmesh studio`;
  // Only what applies to this design: "fairest" for the energies its curves
  // have (GET /api/design's fair_energies), the section for a vessel.
  const energies = design.fair_energies ?? [];
  $('fair-strain').hidden = !energies.includes('strain');
  $('fair-cv').hidden = !energies.includes('curvature_variation');
  $('section-toggle').hidden = design.kind !== 'vessel';
  if (design.kind !== 'vessel') $('section').checked = false;
  showSets(design);
  const params = $('parameters');
  params.replaceChildren();
  if (design.parameters.length === 0) params.textContent = 'The design declares no parameters.';
  for (const p of design.parameters) {
    if (p.kind === 'choice' || p.kind === 'switch') {
      addChoiceControl(params, p);
      continue;
    }
    addControl(params, {name: p.name, label: p.name, value: p.value, min: p.min, max: p.max, step: p.step,
                        description: p.description});
  }
  $('shape-parameters').dataset.keys = '';  // the file's values, even where the keys are the same
  showShapes(design.shape_parameters);
}

// The shape parameters' sliders; a build's list replaces them when it has
// others (a point added or deleted adds or drops a lambda).
function showShapes(shapeParameters) {
  const shapes = $('shape-parameters');
  const keys = JSON.stringify(shapeParameters.map((s) => s.key));
  if (shapes.dataset.keys === keys) return;
  shapes.dataset.keys = keys;
  shapes.replaceChildren();
  $('shape-heading').hidden = shapeParameters.length === 0;
  for (const s of shapeParameters) {
    addControl(shapes, {name: s.key, label: s.key, value: s.value, min: s.min, max: s.max, step: s.step,
                        exclusiveMin: s.min_exclusive});
  }
}

// The preset picker: the design's parameter sets (parameter_sets:). The first
// entry is the design as the file has it (its own `parameter_set`, if any);
// "no set" is offered when the file names one.
const kNoSet = '\u0000none';
function showSets(design) {
  const sets = design.parameter_sets ?? [];
  $('sets').hidden = (design.parameters ?? []).length === 0;
  const select = $('parameter-set');
  select.replaceChildren();
  const add = (value, label) => {
    const option = document.createElement('option');
    option.value = value;
    option.textContent = label;
    select.append(option);
  };
  add('', design.parameter_set ? `(as the file says: ${design.parameter_set})` : '(as the file says)');
  if (design.parameter_set) add(kNoSet, '(no set)');
  for (const name of sets) add(name, name);
  select.disabled = sets.length === 0;
  const picked = state.overrides.parameter_set;
  select.value = picked === undefined ? '' : picked === null ? kNoSet : picked;
}

// A set picked: its values replace the fields' (the fields' own changes are
// dropped, as they would win over the set's values), then built.
function pickSet() {
  remember();
  const value = $('parameter-set').value;
  for (const p of state.design.parameters) delete state.overrides[p.name];
  if (value === '') delete state.overrides.parameter_set;
  else state.overrides.parameter_set = value === kNoSet ? null : value;
  state.syncParameters = true;
  state.lastChanged = 'parameter_set';
  requestBuild();
}

// The values of a build in the parameters' fields (after a set was picked).
function syncFields(parameters) {
  for (const [name, value] of Object.entries(parameters ?? {})) putValue(name, value);
}

// A value into its field: a number's slider and number field, a choice's
// select, a switch's checkbox.
function putValue(name, value) {
  const box = document.getElementById(fieldId(name));
  if (!box) return;
  const select = box.querySelector('select');
  const check = box.querySelector('input[type=checkbox]');
  if (select) select.value = String(value);
  else if (check) check.checked = value === true || value === 'true';
  else for (const input of box.querySelectorAll('input')) input.value = String(Number(Number(value).toPrecision(10)));
}

async function saveSet() {
  const name = window.prompt('Name of the new parameter set (letters, digits, _ and -):');
  if (!name) return;
  const {status, json} = await pageWrites(() => api('POST', '/api/save_set', {name, overrides: state.overrides}));
  if (status !== 200) {
    showError(json.error);
    return;
  }
  // The file changed: read it again, with the new set picked.
  await designTask(async () => {
    if (await loadDesign()) {
      state.overrides.parameter_set = json.parameter_set;
      showSets(state.design);
      state.syncParameters = true;
      requestBuild();
    }
  });
  setStatus(`saved set ${json.parameter_set} in ${json.saved}`);
}

// --- undo, redo and reset ---

// Every change of the values (a field, a dragged point, fairest, a set
// picked, reset) can be undone and redone, back to the file's values as
// last read; an edit that breaks the design is a change like any other.
const history = {past: [], future: [], gesture: null};

function showHistory() {
  state.undoDepth = history.past.length;
  state.redoDepth = history.future.length;
  $('undo').disabled = history.past.length === 0;
  $('redo').disabled = history.future.length === 0;
}

// Before a change: the values as they are, for undo. A slider's drag (the
// same field, until it is let go) is remembered once.
function remember(gesture = null) {
  if (gesture !== null && history.gesture === gesture) return;
  history.gesture = gesture;
  history.past.push(JSON.stringify(state.overrides));
  history.future = [];
  showHistory();
}

function forgetHistory() {
  history.past = [];
  history.future = [];
  history.gesture = null;
  showHistory();
}

// The fields as `overrides` set them, the file's values elsewhere; the
// parameters' values a set gives come with the build (syncParameters).
function showValues() {
  const values = new Map();
  for (const p of state.design.parameters) values.set(p.name, p.kind === 'choice' || p.kind === 'switch' ? p.text : p.value);
  for (const s of state.design.shape_parameters) values.set(s.key, s.value);
  for (const [key, value] of Object.entries(state.overrides)) if (values.has(key)) values.set(key, value);
  for (const [key, value] of values) putValue(key, value);
  showSets(state.design);
}

function restore(overrides) {
  state.overrides = overrides;
  history.gesture = null;
  showValues();
  showHistory();
  state.syncParameters = true;
  state.lastChanged = null;
  requestBuild();
}

function undo() {
  if (history.past.length === 0) return;
  history.future.push(JSON.stringify(state.overrides));
  restore(JSON.parse(history.past.pop()));
}

function redo() {
  if (history.future.length === 0) return;
  history.past.push(JSON.stringify(state.overrides));
  restore(JSON.parse(history.future.pop()));
}

// Back to the file's values (undoable).
function resetValues() {
  if (Object.keys(state.overrides).length === 0) return;
  remember();
  restore({});
}

// Ctrl-Z undoes, Ctrl-Shift-Z (or Ctrl-Y) redoes; in a text or number field
// the browser's own undo of the typing applies.
function onKey(event) {
  if (!(event.ctrlKey || event.metaKey) || event.altKey) return;
  const target = event.target;
  if (target instanceof HTMLInputElement && target.type !== 'range' && target.type !== 'checkbox') return;
  const key = event.key.toLowerCase();
  if (key === 'z' && !event.shiftKey) undo();
  else if ((key === 'z' && event.shiftKey) || key === 'y') redo();
  else return;
  event.preventDefault();
}

// --- errors: pinned to the field that caused them ---

function clearErrors() {
  $('error').hidden = true;
  $('error').textContent = '';
  for (const box of document.querySelectorAll('.control.invalid')) {
    box.classList.remove('invalid');
    box.querySelector('.field-error').textContent = '';
  }
}

function showError(error) {
  clearErrors();
  state.error = error;
  const field = error.field ?? state.lastChanged;
  const box = field ? document.getElementById(fieldId(field)) : null;
  if (box) {
    box.classList.add('invalid');
    box.querySelector('.field-error').textContent = error.message;
  } else {
    $('error').hidden = false;
    $('error').textContent = error.message;
  }
}

// --- the report ---

// Empties the report and gives the function that appends a term and its text.
function reportList() {
  const list = $('report');
  list.replaceChildren();
  return (term, text, cls) => {
    const dt = document.createElement('dt');
    dt.textContent = term;
    const dd = document.createElement('dd');
    dd.textContent = text;
    if (cls) dd.className = cls;
    list.append(dt, dd);
  };
}

function showReport(report, buildMs) {
  const add = reportList();
  const u = report.units;
  if (report.purpose === 'drawing') {
    add('verdict', 'drawing (a curve: no mesh)', 'valid');
  } else {
    add('verdict', report.valid ? 'valid for fabrication' : 'NOT valid', report.valid ? 'valid' : 'not-valid');
    const proofs = [report.topology_proof, report.self_intersection_proof].filter((x) => x);
    if (proofs.length) add('proof', proofs.join('; '));
  }
  if (report.parameter_set) add('parameter set', report.parameter_set);
  add('deviation bound', `${Number(report.max_deviation).toPrecision(3)} ${u} (tolerance ${report.tolerance} ${u})`);
  if (report.volume !== undefined) add('volume', `${Number(report.volume).toPrecision(6)} ${u}³`);
  const box = report.bounding_box;
  if (box) add('size', box.size.map((x) => Number(x).toPrecision(5)).join(' × ') + ` ${box.units ?? u}`);
  const facts = report.build ?? {};
  if (facts.min_clearance !== undefined) {
    add('clearance', `${Number(facts.min_clearance).toPrecision(4)} ${u}` +
        (facts.min_clearance_where ? ` (${facts.min_clearance_where})` : ''));
  }
  if (facts.mould) showMould(add, facts.mould, u);
  if (facts.print?.summary) {
    add('print', facts.print.summary);
    if (facts.print.checked) for (const f of facts.print.findings ?? []) add('print warning', f, 'not-valid');
  }
  if (facts.cnc?.clearance !== undefined) add('tool clearance', `${Number(facts.cnc.clearance).toPrecision(4)} ${u}`);
  if (report.triangles !== undefined) add('triangles', String(report.triangles));
  if (report.pending) {
    add('outputs', `${report.pending.formats.join(', ')}: encoded by export (their files and facts then)`);
  } else if (report.files) {
    add('outputs', report.files.map((f) => f.path).join(', '));
  }
  if (buildMs !== undefined) add('build', `${Math.round(buildMs)} ms`);
}

// A mould's parts, what a potter weighs to make it and cast in it, and which
// way each part leaves its casting case (as `fabmesh run` says them).
function showMould(add, m, u) {
  const g = (x) => String(Number(Number(x).toPrecision(3)));
  const whole = (x) => String(Math.round(Number(x)));
  add('mould', `${m.parts.length} parts, each closed and embedded by construction; slip ` +
      `${Number(m.slip_volume).toPrecision(6)} ${u}³, plaster ${Number(m.plaster_volume).toPrecision(6)} ${u}³`);
  add('casting', `${whole(m.plaster_grams)} g of plaster into ${whole(m.water_grams)} g of water ` +
      `(${g(m.plaster_ratio)} : 1 by weight), ${whole(m.slip_millilitres)} ml of slip ` +
      `(${whole(m.slip_grams)} g at ${g(m.slip_density)} g/ml) to fill it to the spare`);
  if (!m.cases) return;
  const along = (pull) => {
    const k = pull.findIndex((x) => x !== 0);
    return (pull[k] > 0 ? '+' : '-') + 'xyz'[k];
  };
  const made = m.cases.filter((c) => c.refused === undefined).map((c) =>
    `${c.part} lifts out along ${along(c.pull)}` +
    (c.plate ? ` once its plate is off along ${along(c.plate.pull)}` : '') +
    (c.pieces ? ` once its ${c.pieces.length} other piece${c.pieces.length === 1 ? ' is' : 's are'} off` : ''));
  add('casting cases', `${made.length} of ${m.cases.length} parts (${made.length ? made.join(', ') : 'none'})`);
  // The faces the draft leans, part by part.
  const drafted = m.cases.filter((c) => c.draft);
  const faces = drafted.reduce((n, c) => n + c.draft.faces.length, 0);
  const stay = drafted.reduce((n, c) => n + c.draft.not_leaned.length, 0);
  if (faces + stay > 0) {
    const leaned = drafted.filter((c) => c.draft.faces.length)
      .map((c) => [c.part, ...c.draft.faces.map((f) => f.slice(f.lastIndexOf(' ') + 1))].join(' '));
    const taken = drafted.reduce((v, c) => v + c.draft.volume, 0);
    add("casting cases' draft", `${drafted[0].draft.deg} degree${drafted[0].draft.deg === 1 ? '' : 's'} on ${faces} face${faces === 1 ? '' : 's'}` +
        (faces ? ` (${leaned.join(', ')}), taking ${Number(taken.toPrecision(4))} ${u}³ from the parts as cast` : '') +
        (stay ? `; ${stay} more do${stay === 1 ? 'es' : ''} not lean (the report's draft.not_leaned says why)` : ''));
  }
  // The pieces too big for the bed, written in sections.
  const cut = m.cases.flatMap((c) => [c, ...(c.pieces || [])]).filter((p) => p.sections);
  if (cut.length) {
    const pin = cut[0].section_pin;
    const sections = cut.reduce((n, p) => n + p.sections.length, 0);
    add('casting cases cut for the bed', `${cut.length} piece${cut.length === 1 ? '' : 's'} in ${sections} ` +
        `sections (${cut.map((p) => `${p.name} in ${p.sections.length}`).join(', ')}), two ` +
        `${g(pin.diameter)} ${u} pins into ${g(pin.hole_diameter)} ${u} holes across every joint`);
  }
  for (const c of m.cases) if (c.refused !== undefined) add('case refused', c.refused, 'not-valid');
}

// A draft's answer: what it is, and no verdict.
function showDraftReport(answer) {
  const add = reportList();
  add('verdict', 'pending: a draft is shown; the proven mesh and its verdict follow', 'draft');
  add('draft', `${answer.draft.triangles} triangles, tolerance ${answer.draft.tolerance} ` +
      `(coarser than the design's), not validated`);
  add('build', `${Math.round(answer.build_ms)} ms (draft)`);
}

// --- the 3D view (three.js, loaded on demand: the page works without it) ---

// The parts of a mesh that has several (a mould's, a kitchen's pieces), each
// shown or hidden with its checkbox; the choice stays while values change.
state.meshParts = [];    // the shown mesh's parts (an answer's mesh_parts)
state.hiddenParts = [];  // the names hidden

function showParts(names) {
  state.meshParts = names ?? [];
  const box = $('parts');
  box.hidden = state.meshParts.length < 2;
  const layout = JSON.stringify(state.meshParts);
  if (box.dataset.layout === layout) return;
  box.dataset.layout = layout;
  box.replaceChildren();
  for (const name of state.meshParts) {
    const label = document.createElement('label');
    const check = document.createElement('input');
    check.type = 'checkbox';
    check.checked = !state.hiddenParts.includes(name);
    check.dataset.part = name;
    check.addEventListener('change', () => {
      state.hiddenParts = state.hiddenParts.filter((n) => n !== name);
      if (!check.checked) state.hiddenParts.push(name);
      if (view.object) applyHiddenParts(view.object);
      render();
    });
    label.append(check, ` ${name}`);
    box.append(label);
  }
}

function applyHiddenParts(object) {
  const shown = [];
  object.traverse((node) => {
    if (!node.isMesh || !node.userData.part) return;
    node.visible = !state.hiddenParts.includes(node.userData.part);
    if (node.visible) shown.push(node.userData.part);
  });
  state.shownParts = shown;  // the parts drawn (the tests read it)
}

// object: the mesh shown; proven: the last proven build's (kept while a draft is shown); closed:
// the last proven mesh is valid for fabrication (closed, outward), as its draft is taken to be.
const view = {three: null, renderer: null, scene: null, camera: null, controls: null, loader: null, object: null,
              proven: null, material: null, closed: false};

async function setup3d() {
  try {
    const THREE = await import('three');
    const {OrbitControls} = await import('three/addons/controls/OrbitControls.js');
    const {GLTFLoader} = await import('three/addons/loaders/GLTFLoader.js');
    view.three = THREE;
    view.loader = new GLTFLoader();
    view.loader.setRequestHeader({'X-Fabmesh-Token': token});
    const canvas = document.createElement('canvas');
    const context = canvas.getContext('webgl2');
    if (!context) {
      // The meshes are still loaded (and measured); only the picture is missing.
      $('view3d-note').textContent = 'The 3D view needs WebGL 2, which this browser does not offer.';
      return;
    }
    view.renderer = new THREE.WebGLRenderer({canvas, context, antialias: true});
    view.renderer.localClippingEnabled = true;
    $('view3d').append(canvas);
    view.scene = new THREE.Scene();
    view.scene.background = new THREE.Color(0xf4f4f4);
    view.scene.add(new THREE.HemisphereLight(0xffffff, 0x888888, 2.0));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(1, 2, 3);
    view.scene.add(sun);
    // Matte and flat: a CPU's WebGL (SwiftShader, where there is no GPU) draws it in a third of the
    // time of a two-sided MeshStandardMaterial; updateMaterial draws both sides only where needed.
    view.material = new THREE.MeshLambertMaterial({color: 0xc9b79c, flatShading: true, side: THREE.DoubleSide});
    view.material.clippingPlanes = [];
    view.camera = new THREE.PerspectiveCamera(40, 1, 1e-4, 100);
    view.controls = new OrbitControls(view.camera, canvas);
    view.controls.addEventListener('change', render);
    new ResizeObserver(resize).observe($('view3d'));
    resize();
  } catch (e) {
    $('view3d-note').textContent =
        'The 3D view is not available: three.js is not installed with fabmesh (docs/studio.md).';
  }
}

// The section view: the mesh cut by the plane through the vessel's axis
// (model x-z; glTF's y is the model's z), showing the wall and the base.
function sectionPlanes() {
  if (!$('section').checked || !view.three) return [];
  return [new view.three.Plane(new view.three.Vector3(0, 0, -1), 0)];
}

// Back faces are drawn only where they can show: in a section's cut, and on
// a mesh not proven closed and outward (an open surface, an invalid mesh).
// Culling them halves the CPU renderer's work on a closed mesh.
function updateMaterial() {
  if (!view.material) return;
  const planes = sectionPlanes();
  const side = planes.length > 0 || !view.closed ? view.three.DoubleSide : view.three.FrontSide;
  if (side === view.material.side && planes.length === view.material.clippingPlanes.length) return;
  view.material.clippingPlanes = planes;
  view.material.side = side;
  view.material.needsUpdate = true;
}

function updateSection() {
  updateMaterial();
  render();
}

function resize() {
  if (!view.renderer) return;
  const box = $('view3d').getBoundingClientRect();
  view.renderer.setSize(Math.max(1, box.width), Math.max(1, box.height), false);
  view.camera.aspect = Math.max(1, box.width) / Math.max(1, box.height);
  view.camera.updateProjectionMatrix();
  render();
}

function render() {
  if (view.renderer) view.renderer.render(view.scene, view.camera);
}

function signature(object) {
  let sum = 0, count = 0;
  object.traverse((node) => {
    const pos = node.geometry?.attributes?.position;
    if (!pos) return;
    count += pos.count;
    for (let i = 0; i < pos.array.length; i += 7) sum += pos.array[i] * ((i % 13) + 1);
  });
  return `${count}:${sum.toPrecision(12)}`;
}

// A build's mesh as a three.js object, not yet shown.
async function loadMesh(url) {
  if (!view.loader) return null;
  const gltf = await view.loader.loadAsync(url);
  return gltf.scene;
}

function disposeObject(object) {
  object?.traverse((node) => node.geometry?.dispose());
}

// Shows `object` (the mesh at `url`) in place of the one shown. The last
// proven mesh is kept while a draft is shown, to be shown again when the
// draft's values do not build.
function placeMesh(object, url, draft) {
  if (!object) return;
  state.mesh = url;
  state.meshSignature = signature(object);
  state.rendered = view.renderer !== null;
  state.draft = draft;
  $('draft-note').hidden = !draft;
  const first = view.proven === null && view.object === null;
  const old = [view.object, view.proven];
  if (view.object && view.object !== object) view.scene?.remove(view.object);
  if (!draft) view.proven = object;
  view.object = object;
  for (const o of old) if (o && o !== view.object && o !== view.proven) disposeObject(o);
  if (!view.renderer) return;
  object.traverse((node) => {
    if (!node.isMesh) return;
    // A part's primitive carries its name as its material's (mesh_parts).
    node.userData.part = node.material?.name ?? '';
    node.material = view.material;
  });
  applyHiddenParts(object);
  view.scene.add(object);
  if (first) {
    const THREE = view.three;
    const box = new THREE.Box3().setFromObject(object);
    const size = box.getSize(new THREE.Vector3()).length();
    const centre = box.getCenter(new THREE.Vector3());
    view.controls.target.copy(centre);
    view.camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.5, 0.9).multiplyScalar(size));
    view.camera.near = size / 1000;
    view.camera.far = size * 100;
    view.camera.updateProjectionMatrix();
    view.controls.update();
  }
  render();
}

// --- points typed, added and deleted ---
//
// Each curve whose points the plot offers (an answer's control_points) has a
// row per point: its x and y to type, and for a quasi-B-spline's list a ×
// that deletes it; a double-click on the plot near a curve's control polygon
// (or its through points) adds a point there. A point typed or dragged is
// its own -D path's value (`profile.points[2]`); adding or deleting one
// replaces the curve's whole list (`profile.points`) and its lambdas (a new
// inner point gets lambda 0), each point and lambda as the file writes it,
// expressions kept. Every one is a change that undo takes back.

const round6 = (v) => Number(Number(v).toPrecision(6));

// A point's value now: its own override, else the text the answer gives.
function pointText(curve, key) {
  const given = state.overrides[key];
  return given === undefined ? curve.points.find((q) => q.key === key).text : String(given);
}

// Every point's value now, in order.
function pointTexts(curve) {
  return curve.points.map((p) => pointText(curve, p.key));
}

function lambdaTexts(curve) {
  if (!curve.lambdas) return null;
  const key = curve.lambdas.key;
  return curve.lambdas.texts.map((t, k) => {
    const given = state.overrides[`${key}[${k}]`];
    return given === undefined ? t : String(given);
  });
}

// The override of a whole list (its items' own overrides folded in), put
// last: an item's override set later applies on top of it.
function putList(key, texts) {
  for (const k of Object.keys(state.overrides)) if (k === key || k.startsWith(key + '[')) delete state.overrides[k];
  state.overrides[key] = `[${texts.join(', ')}]`;
}

function setPoint(curve, index, x, y) {
  remember();
  const key = curve.points[index].key;
  state.overrides[key] = `[${round6(x)}, ${round6(y)}]`;
  state.lastChanged = key;
  requestBuild();
}

function deletePoint(curve, index) {
  const n = curve.points.length;
  if (!curve.list || n <= curve.min_points) return;
  remember();
  const texts = pointTexts(curve);
  const lambdas = lambdaTexts(curve);
  texts.splice(index, 1);
  // The lambda of the point that stops being an inner one: its own, or its neighbour's at an end.
  if (lambdas) lambdas.splice(Math.min(Math.max(index - 1, 0), n - 3), 1);
  putList(curve.list, texts);
  if (lambdas) putList(curve.lambdas.key, lambdas);
  state.lastChanged = curve.list;
  requestBuild();
}

function insertPoint(curve, at, x, y) {
  const n = curve.points.length;
  remember();
  const texts = pointTexts(curve);
  const lambdas = lambdaTexts(curve);
  texts.splice(at, 0, `[${round6(x)}, ${round6(y)}]`);
  if (lambdas) lambdas.splice(Math.min(Math.max(at - 1, 0), n - 2), 0, '0');
  putList(curve.list, texts);
  if (lambdas) putList(curve.lambdas.key, lambdas);
  state.lastChanged = curve.list;
  requestBuild();
}

// A composite's segments (an answer's `segments`: each one's entries as
// the file writes them, one-line YAML, and the keys of the points it
// gives). A segment is deleted from the row of its end point; a
// double-click near the curve adds a segment that ends there, before the
// segment it lands on: a copy of that segment's entries (its join, family,
// shape parameters) whose given points are scaled into the new stretch. The
// whole list is one override (`outline.segments`), each kept segment as
// written, its points' and shape parameters' own overrides folded in.

const position = (curve, key) => {
  const p = curve.points.find((q) => q.key === key);
  return p ? {x: p.x, y: p.y} : null;
};

// The segment's entries as a flow map, `points` replaced when given.
function segmentText(curve, item, points = null) {
  const parts = item.entries.map(([name, value]) => {
    if (name === 'points') return `points: [${(points ?? item.points.map((key) => pointText(curve, key))).join(', ')}]`;
    const given = state.overrides[`${item.key}.${name}`];
    return `${name}: ${given === undefined ? value : String(given)}`;
  });
  return `{${parts.join(', ')}}`;
}

// Where segment s starts: the end of the one before it (of the last one, on
// a closed curve), or its own first point when it is explicit.
function segmentStart(curve, s) {
  const items = curve.segments.items;
  const item = items[s];
  if (!item.joined) return position(curve, item.points[0]);
  const before = s > 0 ? items[s - 1] : curve.segments.closed ? items[items.length - 1] : null;
  return before ? position(curve, before.points[before.points.length - 1]) : null;
}

function putSegments(curve, texts) {
  putList(curve.segments.key, texts);
  state.lastChanged = curve.segments.key;
  requestBuild();
}

function deleteSegment(curve, s) {
  const items = curve.segments.items;
  remember();
  putSegments(curve, items.filter((_, k) => k !== s).map((item) => segmentText(curve, item)));
}

// A segment ending at `at`, before segment s (which then starts there).
function insertSegment(curve, s, at) {
  const items = curve.segments.items;
  const item = items[s];
  const start = segmentStart(curve, s);
  const end = position(curve, item.points[item.points.length - 1]);
  if (!start || !end) return;
  const r = Math.min(Math.max(Math.hypot(at.x - start.x, at.y - start.y) /
                              Math.max(Math.hypot(end.x - start.x, end.y - start.y), 1e-300), 0.05), 0.95);
  const given = item.points.map((key) => position(curve, key));
  const text = (p) => `[${round6(p.x)}, ${round6(p.y)}]`;
  // The points before the end: a handle near the start keeps its direction
  // from the start, one near the end its direction to the end, both scaled.
  const near = (p, from, to, scale) => ({x: to.x + (p.x - from.x) * scale, y: to.y + (p.y - from.y) * scale});
  const k = given.length;
  const points = given.map((p, i) => {
    if (i === k - 1) return text(at);
    if (!item.joined && i === 0) return text(start);
    const leading = item.joined ? k === 3 && i === 0 : i === 1;  // Q1 of a G0 join, P1 of an explicit one
    return text(leading ? near(p, start, start, r) : near(p, end, at, r));
  });
  const texts = items.map((it) => segmentText(curve, it));
  let kept = texts[s];
  if (!item.joined) {
    // The explicit segment now starts where the new one ends, at a corner.
    const moved = item.points.map((key, i) => (i === 0 ? text(at) : pointText(curve, key)));
    kept = segmentText(curve, {...item, entries: item.entries.filter(([name]) => name !== 'continuity')}, moved);
  }
  const added = segmentText(curve, item, points);  // its shape parameters as they are now
  texts.splice(s, 1, added, kept);
  remember();
  putSegments(curve, texts);
}

function showPoints(controlPoints) {
  const curves = controlPoints ?? [];
  state.controlPoints = curves;
  $('points-heading').hidden = curves.length === 0;
  $('points-help').hidden = !curves.some((c) => c.list);
  const box = $('points');
  const layout = JSON.stringify(curves.map((c) => [c.curve, c.points.map((p) => p.key)]));
  if (box.dataset.layout === layout) {
    // The same rows: the new positions, except in a field being typed in.
    for (const curve of curves) {
      for (const p of curve.points) {
        const row = document.getElementById(fieldId(p.key));
        if (!row) continue;
        const [x, y] = row.querySelectorAll('input');
        if (document.activeElement !== x) x.value = String(round6(p.x));
        if (document.activeElement !== y) y.value = String(round6(p.y));
      }
    }
    return;
  }
  box.dataset.layout = layout;
  box.replaceChildren();
  for (const curve of curves) {
    const group = document.createElement('div');
    group.className = 'control point-list';
    group.id = fieldId(curve.list ?? curve.curve);  // an error of the whole list is shown here
    const title = document.createElement('label');
    title.textContent = curve.group === 'through-points' ? `${curve.curve} (through)` : curve.curve;
    const err = document.createElement('div');
    err.className = 'field-error';
    // The columns: a vessel's profile is drawn in (r, z).
    const axes = state.design?.kind === 'vessel' ? ['r', 'z'] : ['x', 'y'];
    const head = document.createElement('div');
    head.className = 'row axes';
    head.textContent = `${axes[0]}, ${axes[1]} (${state.design?.units ?? ''})`;
    group.append(title, err, head);
    box.append(group);
    curve.points.forEach((p, i) => {
      const row = document.createElement('div');
      row.className = 'control point';
      row.id = fieldId(p.key);
      row.dataset.key = p.key;
      const line = document.createElement('div');
      line.className = 'row';
      const label = document.createElement('span');
      label.textContent = curve.list ? String(i) : p.key.slice(curve.curve.length + 1);
      label.title = p.key;
      const inputs = [p.x, p.y].map((v, axis) => {
        const input = document.createElement('input');
        input.type = 'number';
        input.step = 'any';
        input.value = String(round6(v));
        input.setAttribute('aria-label', `${p.key} ${axis === 0 ? 'x' : 'y'}`);
        return input;
      });
      const typed = () => {
        const [x, y] = inputs.map((input) => Number(input.value));
        if (inputs.some((input) => input.value === '') || !Number.isFinite(x) || !Number.isFinite(y)) return;
        // The answer's curve, not this closure's: rows stay while the answers change.
        const now = state.controlPoints.find((c) => c.curve === curve.curve);
        if (now && now.points[i]) setPoint(now, i, x, y);
      };
      for (const input of inputs) input.addEventListener('change', typed);
      line.append(label, ...inputs);
      const segment = curve.segments?.items.findIndex((item) => item.points[item.points.length - 1] === p.key) ?? -1;
      if (segment >= 0) {
        const items = curve.segments.items;
        const remove = document.createElement('button');
        remove.type = 'button';
        remove.textContent = '×';
        remove.title = `Delete ${items[segment].key}, which ends here`;
        remove.setAttribute('aria-label', `delete ${items[segment].key}`);
        // A curve keeps a segment (two when closed); an open curve's first stays explicit.
        remove.disabled = items.length <= (curve.segments.closed ? 2 : 1) ||
                          (!curve.segments.closed && segment === 0 && items.length > 1 && items[1].joined);
        remove.addEventListener('click', () => {
          const now = state.controlPoints.find((c) => c.curve === curve.curve);
          if (now?.segments) deleteSegment(now, segment);
        });
        line.append(remove);
      }
      if (curve.list) {
        const remove = document.createElement('button');
        remove.type = 'button';
        remove.textContent = '×';
        remove.title = `Delete ${p.key}`;
        remove.setAttribute('aria-label', `delete ${p.key}`);
        remove.disabled = curve.points.length <= curve.min_points;
        remove.addEventListener('click', () => {
          const now = state.controlPoints.find((c) => c.curve === curve.curve);
          if (now) deletePoint(now, i);
        });
        line.append(remove);
      }
      const rowErr = document.createElement('div');
      rowErr.className = 'field-error';
      row.append(line, rowErr);
      group.append(row);
    });
  }
}

// How far `p` is from the leg a-b, and where along it (t in [0, 1] on it).
function distanceToLeg(p, a, b) {
  const dx = b.x - a.x, dy = b.y - a.y;
  const t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / Math.max(dx * dx + dy * dy, 1e-300);
  const c = Math.min(Math.max(t, 0), 1);
  return {d: Math.hypot(p.x - a.x - c * dx, p.y - a.y - c * dy), t};
}

// A double-click on the plot: a point added to the curve whose polygon (or
// line of through points) passes nearest, within 40 pixels, on its nearest
// leg, or before its first or after its last point when the click is beyond
// that end.
function addPointAt(event) {
  const svg = $('plot').querySelector('svg');
  if (!svg) return;
  let best = null;
  for (const curve of state.controlPoints) {
    if (curve.segments) {
      const group = svg.querySelector(`g.control-polygon[data-name="${CSS.escape(curve.curve)}"]`);
      const ctm = group?.getScreenCTM();
      if (!ctm) continue;
      const q = new DOMPoint(event.clientX, event.clientY).matrixTransform(ctm.inverse());
      const at = {x: q.x, y: -q.y};
      const pixels = Math.hypot(ctm.a, ctm.b);
      curve.segments.items.forEach((item, s) => {
        // The segment's start, then the points it gives: its polygon as far as the page knows it.
        const chain = [segmentStart(curve, s), ...item.points.map((key) => position(curve, key))]
                          .filter((p) => p !== null);
        for (let k = 0; k + 1 < chain.length; ++k) {
          const d = distanceToLeg(at, chain[k], chain[k + 1]).d * pixels;
          if (!best || d < best.d) best = {d, curve, segment: s, at};
        }
      });
      continue;
    }
    if (!curve.list) continue;
    const group = svg.querySelector(`g.${curve.group}[data-name="${CSS.escape(curve.curve)}"]`);
    const ctm = group?.getScreenCTM();
    if (!ctm) continue;
    const q = new DOMPoint(event.clientX, event.clientY).matrixTransform(ctm.inverse());
    const at = {x: q.x, y: -q.y};
    const pixels = Math.hypot(ctm.a, ctm.b);  // screen pixels per plot unit
    const pts = curve.points;
    for (let k = 0; k + 1 < pts.length; ++k) {
      const leg = distanceToLeg(at, pts[k], pts[k + 1]);
      const t = leg.t;
      const d = leg.d * pixels;
      let index = k + 1;
      if (k === 0 && t < 0) index = 0;
      if (k + 2 === pts.length && t > 1) index = pts.length;
      if (!best || d < best.d) best = {d, curve, index, at};
    }
  }
  if (!best || best.d > 40) {
    setStatus('double-click nearer a control polygon to add a point');
    return;
  }
  event.preventDefault();
  if (best.segment !== undefined) insertSegment(best.curve, best.segment, best.at);
  else insertPoint(best.curve, best.index, best.at.x, best.at.y);
}

// --- control points dragged on the plot ---

// The plot's control-point circles of each curve whose points the design
// writes one by one (GET /api/design's control_points; for a curve given
// `through:` points, the dots on its joints), made draggable: a drop sets
// the point's -D path ("profile.points[2]", "profile.through[1]",
// "outline.segments[1].points[0]") and builds.
function enableDragging(controlPoints) {
  const svg = $('plot').querySelector('svg');
  if (!svg || !state.design) return;
  for (const curve of controlPoints ?? state.design.control_points) {
    // A curve's control polygon, or the dots of the points it passes through.
    const kind = curve.group ?? 'control-polygon';
    const group = svg.querySelector(`g.${kind}[data-name="${CSS.escape(curve.curve)}"]`);
    if (!group) continue;
    const circles = [...group.querySelectorAll('circle.control-point, circle.through-point')];
    // Each circle with the point it draws: one to one in order, or (a
    // segment curve's given points) every circle drawn where the point is.
    const pairs = [];
    if (curve.by === 'position') {
      // The plot writes coordinates to a fixed number of decimals: a tenth of a
      // circle's radius (a quarter pixel) tells the point it draws.
      for (const point of curve.points) {
        for (const circle of circles) {
          const within = Number(circle.getAttribute('r')) / 10;
          if (Math.abs(Number(circle.getAttribute('cx')) - point.x) <= within &&
              Math.abs(-Number(circle.getAttribute('cy')) - point.y) <= within)
            pairs.push([circle, point]);
        }
      }
    } else if (circles.length === curve.points.length) {
      circles.forEach((circle, i) => pairs.push([circle, curve.points[i]]));
    }
    if (pairs.length === 0) continue;
    group.parentNode.appendChild(group);  // above the curve and its joint markers, to be grabbed
    for (const [circle, point] of pairs) {
      circle.classList.add('draggable');
      circle.setAttribute('r', String(Number(circle.getAttribute('r')) * 2.5));  // easier to grab
      circle.dataset.key = point.key;
      circle.addEventListener('pointerdown', (event) => drag(event, circle));
    }
  }
}

function drag(event, circle) {
  event.preventDefault();
  circle.setPointerCapture(event.pointerId);
  // Screen to the plot's model frame (the circles' cy is -y).
  const model = (e) => {
    const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(circle.getScreenCTM().inverse());
    return {x: p.x, y: -p.y};
  };
  const start = {cx: circle.getAttribute('cx'), cy: circle.getAttribute('cy')};
  const move = (e) => {
    const p = model(e);
    circle.setAttribute('cx', String(p.x));
    circle.setAttribute('cy', String(-p.y));
  };
  const drop = (e) => {
    circle.removeEventListener('pointermove', move);
    circle.removeEventListener('pointerup', drop);
    // A click (a double-click's halves) moves nothing.
    if (Math.hypot(e.clientX - event.clientX, e.clientY - event.clientY) < 2) {
      circle.setAttribute('cx', start.cx);
      circle.setAttribute('cy', start.cy);
      return;
    }
    const p = model(e);
    remember();
    state.overrides[circle.dataset.key] = `[${round6(p.x)}, ${round6(p.y)}]`;
    state.lastChanged = circle.dataset.key;
    requestBuild();
  };
  circle.addEventListener('pointermove', move);
  circle.addEventListener('pointerup', drop);
}

// --- builds: one at a time per kind, the newest values next ---
//
// A design whose proven mesh is large (more than kDraftTriangles triangles,
// the last proven build's count) gets a draft first: the same values built
// at a coarser tolerance (POST /api/build with "draft": true), shown at once
// and labelled as a draft, with no verdict; the proven build, asked for once
// the draft is drawn (both at once made the draft a third slower on two
// cores, and the proven one no faster), replaces it with its mesh and its
// verdict. A draft never replaces what is shown for newer values, nor comes
// after its own values' proven answer; its errors are not shown (the proven
// build's are).

const kDraftTriangles = 40000;
const lanes = {proven: {busy: false, pending: false}, draft: {busy: false, pending: false}};
state.change = 0;      // bumped by every change of the values
state.shownChange = 0; // the change whose plot and mesh are shown
state.provenChange = 0;// the change whose proven build is shown (its verdict in the report)
state.draft = false;   // the shown mesh is a draft
state.drafts = 0;      // drafts shown
let useDrafts = false;
let settled = 0;       // the newest change whose proven build answered (valid or not): no draft of it any more
let proven = null;     // the last proven build's answer, shown again when a draft's values fail
let provenAfterDraft = false;  // a proven build waits for the draft's answer (the cores are the draft's first)

function requestBuild() {
  state.change += 1;
  if (!useDrafts) {
    runLane('proven');
  } else {
    provenAfterDraft = true;
    runLane('draft');
  }
}

function runLane(kind) {
  const lane = lanes[kind];
  if (lane.busy) {
    lane.pending = true;
    return;
  }
  kind === 'draft' ? draftBuild() : build();
}

function finishLane(kind) {
  const lane = lanes[kind];
  lane.busy = false;
  if (lane.pending) runLane(kind);
}

// The plot of an answer, with its draggable points where that answer's values
// put them; below the 3D view, a kitchen's slab layout (its pieces as nested)
// and a countertop's router paths (each program's tool-centre path over the
// loops it cuts, as the toolpath_svg output draws it).
function showPlot(answer) {
  state.plotSvg = answer.plot_svg;
  $('plot').innerHTML = answer.plot_svg;
  enableDragging(answer.control_points);
  showPoints(answer.control_points ?? state.design?.control_points);
  const layout = $('layout');
  layout.hidden = !answer.layout_svg;
  layout.innerHTML = answer.layout_svg ?? '';
  const router = $('router');
  const programs = answer.router_paths ?? [];
  router.hidden = programs.length === 0;
  router.replaceChildren();
  for (const program of programs) {
    const figure = document.createElement('figure');
    figure.className = 'router-path';
    figure.dataset.program = program.program;
    const caption = document.createElement('figcaption');
    caption.textContent = `router path: ${program.program}.nc` +
        (program.parts.length ? ` (${program.parts.join(', ')})` : '');
    figure.innerHTML = program.svg;
    figure.prepend(caption);
    router.append(figure);
  }
  state.routerPrograms = programs.map((p) => p.program);
}

async function draftBuild() {
  lanes.draft.busy = true;
  lanes.draft.pending = false;
  const change = state.change;
  const overrides = {...state.overrides};
  try {
    const {status, json} = await api('POST', '/api/build', {overrides, draft: true});
    // Shown only while nothing newer is, and before its proven build answers (even with an error).
    const late = () => change <= Math.max(state.shownChange, settled);
    if (status !== 200 || late() || !json.mesh) return;
    const object = await loadMesh(json.mesh);
    if (late()) {
      disposeObject(object);
      return;
    }
    clearErrors();
    showPlot(json);
    showDraftReport(json);
    showParts(json.mesh_parts);
    placeMesh(object, json.mesh, true);
    state.shownChange = change;
    state.drafts += 1;
    setStatus(`draft in ${Math.round(json.build_ms)} ms; proving…`);
  } catch (e) {
    // The proven build says what is wrong.
  } finally {
    finishLane('draft');
    if (provenAfterDraft) {
      provenAfterDraft = false;
      // Once the frame with the draft is drawn: the proven build takes both
      // cores of a small machine, and the CPU renderer's draw of the draft
      // waited for them.
      requestAnimationFrame(() => requestAnimationFrame(() => runLane('proven')));
    }
  }
}

async function build() {
  lanes.proven.busy = true;
  lanes.proven.pending = false;
  const change = state.change;
  const overrides = {...state.overrides};
  if (!useDrafts) setStatus('building…');
  const start = performance.now();
  const since = () => performance.now() - start;
  try {
    const {status, json} = await api('POST', '/api/build', {overrides});
    settled = Math.max(settled, change);
    if (status === 200) {
      const timings = {answer: since()};
      const object = json.mesh ? await loadMesh(json.mesh) : null;
      timings.mesh = since();
      if (change >= state.shownChange) {  // a draft of newer values may have come while the mesh loaded
        clearErrors();
        state.error = null;
        showPlot(json);
        timings.plot = since();
        showReport(json.report, json.build_ms);
        if (json.shape_parameters) showShapes(json.shape_parameters);
        state.lastReport = json.report;
        if (state.syncParameters) {
          syncFields(json.report.parameters);
          state.syncParameters = false;
        }
        timings.report = since();
        view.closed = json.report.purpose === 'fabrication' && json.report.valid === true;
        updateMaterial();
        showParts(json.mesh_parts);
        if (object) placeMesh(object, json.mesh, false);
        state.shownChange = change;
        state.provenChange = change;
        timings.shown = since();
        state.timings = timings;
        setStatus(`built in ${Math.round(json.build_ms)} ms`);
        proven = json;
      } else if (object) {
        disposeObject(object);
      }
      useDrafts = (json.report.triangles ?? 0) > kDraftTriangles;
      state.validBuilds += 1;
    } else if (change >= state.shownChange) {  // else a draft of newer values is shown
      // The last valid shape stays shown (again, when a draft of these values was); the error goes to its field.
      state.errors += 1;
      if (state.draft) restoreProven();
      showError(json.error ?? {message: `HTTP ${status}`});
      setStatus('the design does not build with these values');
    } else {
      state.errors += 1;
    }
  } catch (e) {
    state.errors += 1;
    showError({message: String(e)});
  } finally {
    state.settledChange = Math.max(state.settledChange, change);
    state.builds += 1;
    document.body.dataset.builds = String(state.builds);
    finishLane('proven');
  }
}

// A draft of values that do not build: the last proven build's plot, report and mesh again.
function restoreProven() {
  if (!proven) return;
  showPlot(proven);
  showReport(proven.report, proven.build_ms);
  showParts(proven.mesh_parts);
  if (view.proven) placeMesh(view.proven, proven.mesh, false);
  state.shownChange = state.provenChange;
}

// --- save, export, and the file watched ---

async function save() {
  const {status, json} = await api('POST', '/api/save', {overrides: state.overrides});
  if (status === 200) {
    setStatus(`saved ${json.saved}`);
  } else {
    showError(json.error);
  }
}

async function exportOutputs() {
  setStatus('exporting…');
  const {status, json} = await api('POST', '/api/export', {overrides: state.overrides});
  const list = $('exported');
  list.replaceChildren();
  if (status !== 200) {
    showError(json.error);
    return;
  }
  for (const file of json.files) {
    const li = document.createElement('li');
    li.textContent = file;
    list.append(li);
  }
  // The export's report is complete: the outputs' facts too.
  if (state.provenChange === state.change) showReport(json.report);
  setStatus(`exported ${json.files.length} files to ${json.out_dir}`);
}

// The papers' fairest shape parameters for the current control points: set
// in their fields, then built.
async function fairest(energy) {
  const {status, json} = await api('POST', '/api/fairest', {overrides: state.overrides, energy});
  if (status !== 200) {
    showError(json.error);
    return;
  }
  remember();
  for (const [key, value] of Object.entries(json.overrides)) {
    state.overrides[key] = value;
    const box = document.getElementById(fieldId(key));
    if (!box) continue;
    for (const input of box.querySelectorAll('input')) input.value = String(Number(value.toPrecision(6)));
  }
  const skipped = json.skipped.map((s) => `${s.curve}: ${s.reason}`).join('; ');
  setStatus(`fairest (${energy.replace('_', ' ')}): ${Object.keys(json.overrides).length} values` +
            (skipped ? `; skipped ${skipped}` : ''));
  state.lastChanged = null;
  requestBuild();
}

async function loadDesign() {
  const {status, json} = await api('GET', '/api/design');
  if (status !== 200) {
    showError(json.error);
    return false;
  }
  state.design = json;
  state.version = json.version;
  state.overrides = {};
  forgetHistory();
  showControls(json);
  return true;
}

// Reading the design file back is one task at a time, whether the watcher
// saw an edit or the page wrote the file itself. A version the watcher asked
// for while the page was writing is not taken for an editor's edit: read
// after the page's own read, it would drop the set the page just picked.
const designReads = {queue: Promise.resolve(), writing: 0, writes: 0};

function designTask(task) {
  const run = designReads.queue.then(task);
  designReads.queue = run.catch(() => {});
  return run;
}

async function pageWrites(write) {
  designReads.writing += 1;
  try {
    return await write();
  } finally {
    designReads.writing -= 1;
    designReads.writes += 1;
  }
}

// The design file changed (saved here or in an editor): show what it says now.
async function watch() {
  try {
    const writes = designReads.writes;
    if (designReads.writing > 0) return;
    const {status, json} = await api('GET', '/api/version');
    if (status !== 200 || designReads.writing > 0 || designReads.writes !== writes) return;
    await designTask(async () => {
      if (json.version !== state.version && (await loadDesign())) requestBuild();
    });
  } finally {
    setTimeout(watch, 250);
  }
}

$('save').addEventListener('click', save);
$('undo').addEventListener('click', undo);
$('redo').addEventListener('click', redo);
$('reset').addEventListener('click', resetValues);
document.addEventListener('keydown', onKey);
$('parameter-set').addEventListener('change', pickSet);
$('save-set').addEventListener('click', saveSet);
$('section').addEventListener('change', updateSection);
$('plot').addEventListener('dblclick', addPointAt);
$('fair-strain').addEventListener('click', () => fairest('strain'));
$('fair-cv').addEventListener('click', () => fairest('curvature_variation'));
$('export').addEventListener('click', exportOutputs);
await setup3d();
if (await loadDesign()) requestBuild();
setTimeout(watch, 250);
