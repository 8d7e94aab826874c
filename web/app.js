// The page of `dynosize serve` (docs/web.md): plain JavaScript over the JSON API, no build step.
// Every number shown comes from the API, which answers what the CLI prints with --json.
"use strict";

const $ = (id) => document.getElementById(id);

// One API call: GET without a body, POST with a JSON body. Throws an Error carrying the server's
// one-line message (the CLI's) when the answer is not 200.
async function api(path, body) {
  const init = body === undefined ? {} : {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) };
  const res = await fetch(path, init);
  const text = await res.text();
  let doc;
  try { doc = JSON.parse(text); } catch (e) { throw new Error(`${path}: HTTP ${res.status}: ${text.slice(0, 200)}`); }
  if (!res.ok) throw new Error(doc.error || `${path}: HTTP ${res.status}`);
  return doc;
}

function showError(id, err) {
  const el = $(id);
  if (!err) { el.hidden = true; el.textContent = ""; return; }
  el.hidden = false;
  el.textContent = err.message || String(err);
}

const fmt = (v, digits) => (typeof v === "number" && isFinite(v) ? v.toFixed(digits) : "-");
function cell(tr, text, cls) {
  const td = document.createElement("td");
  td.textContent = text;
  if (cls) td.className = cls;
  tr.appendChild(td);
  return td;
}
function header(table, names) {
  table.replaceChildren();
  const tr = document.createElement("tr");
  for (const [name, cls] of names) {
    const th = document.createElement("th");
    th.textContent = name;
    if (cls) th.className = cls;
    tr.appendChild(th);
  }
  const thead = document.createElement("thead");
  thead.appendChild(tr);
  table.appendChild(thead);
  const tbody = document.createElement("tbody");
  table.appendChild(tbody);
  return tbody;
}

// --- tabs
function showView(name) {
  for (const b of document.querySelectorAll(".tab")) b.classList.toggle("active", b.dataset.view === name);
  for (const v of document.querySelectorAll(".view")) v.hidden = v.id !== `view-${name}`;
  if (name === "catalog" && !$("cat-table").rows.length) listCatalog();
  if (name === "mission" && !$("mission-example").options.length) loadExamples();
}

// --- the catalog, one kind at a time, fetched once
const catalogCache = {};
async function catalogKind(kind) {
  if (!catalogCache[kind]) catalogCache[kind] = api(`/api/catalog?kind=${kind}`).then((d) => d[kind]);
  return catalogCache[kind];
}
function nameOf(kind, id) {
  const list = catalogCache[`${kind}:resolved`];
  const e = list && list.find((x) => x.id === id);
  return e ? e.name : "";
}

// A searchable picker: the select lists the entries whose id or name holds the filter's words
// (at most 300, the chosen one always kept).
function picker(filterId, selectId, entries, chosen, allowNone) {
  const filter = $(filterId), select = $(selectId);
  const fill = () => {
    const words = filter.value.toLowerCase().split(/\s+/).filter(Boolean);
    const current = select.value || chosen;
    select.replaceChildren();
    if (allowNone) select.add(new Option("(none: the motor's table)", ""));
    let n = 0;
    for (const e of entries) {
      const text = `${e.id}  ${e.name}`.toLowerCase();
      const keep = e.id === current || (n < 300 && words.every((w) => text.includes(w)));
      if (!keep) continue;
      select.add(new Option(`${e.name} (${e.id})`, e.id, false, e.id === current));
      n += 1;
    }
  };
  filter.addEventListener("input", fill);
  fill();
}

// --- drive calculator
const charts = {};
function lineChart(id, label, unit, xs, ys) {
  if (typeof Chart === "undefined") return;
  if (charts[id]) charts[id].destroy();
  charts[id] = new Chart($(id), {
    type: "line",
    data: { labels: xs, datasets: [{ label, data: ys, borderColor: "#0b5cad", backgroundColor: "#0b5cad", tension: 0.2 }] },
    options: {
      animation: false, responsive: true, maintainAspectRatio: false,
      plugins: { legend: { display: false }, title: { display: true, text: `${label} vs throttle` } },
      scales: { x: { title: { display: true, text: "throttle %" } }, y: { title: { display: true, text: unit } } },
    },
  });
}

function driveRequest() {
  const body = { motor: $("motor").value, esc: $("esc").value, vdc_v: Number($("vdc").value) };
  if ($("prop").value) {
    body.prop = $("prop").value;
    body.rho_kg_m3 = Number($("rho").value);
  }
  return body;
}

function renderPropTable(doc) {
  const rows = doc.throttles;
  const tbody = header($("drive-table"), [["TR %"], ["rpm"], ["thrust N"], ["thrust gf"], ["IDC A"], ["Irms A"],
    ["PDC W"], ["Pmech W"], ["g/W"], ["η motor"], ["η ESC"], ["η system"], ["FM"], ["limits", "text"]]);
  for (const r of rows) {
    const tr = tbody.insertRow();
    const flags = [...r.limits];
    if (r.saturated) flags.push("esc_saturated");
    if (!r.prop_in_data) flags.push("prop_data_edge");
    [fmt(100 * r.throttle, 0), fmt(r.rpm, 0), fmt(r.thrust_n, 2), fmt(r.thrust_n / 0.00980665, 0), fmt(r.idc_a, 2),
      fmt(r.irms_a, 2), fmt(r.pdc_w, 1), fmt(r.pmech_w, 1), fmt(r.g_per_w, 2), fmt(r.eta_motor, 3), fmt(r.eta_esc, 3),
      fmt(r.eta_system, 3), fmt(r.figure_of_merit, 3)].forEach((t) => cell(tr, t));
    cell(tr, flags.length ? flags.join(", ") : "-", "text");
  }
  const xs = rows.map((r) => fmt(100 * r.throttle, 0));
  lineChart("chart-thrust", "thrust", "N", xs, rows.map((r) => r.thrust_n));
  lineChart("chart-current", "battery current IDC", "A", xs, rows.map((r) => r.idc_a));
}

function renderMotorTable(doc) {
  const rows = doc.throttles;
  const tbody = header($("drive-table"), [["TR %"], ["TR eff %"], ["no-load rpm"], ["stall N·m"], ["max-P rpm"],
    ["max P W"], ["best-η rpm"], ["η system"], ["IDC A at best η"]]);
  for (const r of rows) {
    const tr = tbody.insertRow();
    [fmt(100 * r.throttle, 0), fmt(100 * r.throttle_effective, 1), fmt(r.no_load_rpm, 0), fmt(r.stall_torque_nm, 4),
      fmt(r.max_power_rpm, 0), fmt(r.max_power_w, 1), fmt(r.max_efficiency_rpm, 0), fmt(r.max_eta_system, 3),
      fmt(r.at_max_efficiency.idc_a, 2)].forEach((t) => cell(tr, t));
  }
  const xs = rows.map((r) => fmt(100 * r.throttle, 0));
  lineChart("chart-thrust", "maximum shaft power", "W", xs, rows.map((r) => r.max_power_w));
  lineChart("chart-current", "IDC at best efficiency", "A", xs, rows.map((r) => r.at_max_efficiency.idc_a));
}

// The system-efficiency map over torque and speed at the pack voltage (as simulate --plot's
// efficiency map): one array request of the inverse model (torque and rpm given, throttle
// solved) on a 36 x 28 grid framed by the propeller's line, which is drawn over it. Points the
// drive cannot hold (throttle above one, a limit) are left out.
function etaColor(eta, lo, hi) {
  const t = Math.max(0, Math.min(1, (eta - lo) / Math.max(hi - lo, 1e-9)));
  const hue = 240 - 240 * t;  // blue (low) .. red (high)
  return `hsl(${hue.toFixed(0)}, 75%, 50%)`;
}

async function renderEfficiencyMap(doc) {
  if (typeof Chart === "undefined" || !doc.prop) return;
  const rows = doc.throttles.filter((r) => r.rpm > 0 && r.torque_nm > 0);
  if (!rows.length) return;
  const rpmMax = 1.15 * Math.max(...rows.map((r) => r.rpm)), qMax = 1.3 * Math.max(...rows.map((r) => r.torque_nm));
  const rpm = [], torque = [];
  for (let i = 1; i <= 36; i++) {
    for (let j = 1; j <= 28; j++) {
      rpm.push((rpmMax * i) / 36);
      torque.push((qMax * j) / 28);
    }
  }
  const grid = await api("/api/simulate", { motor: doc.motor, esc: doc.esc, vdc_v: doc.vdc_v, rpm, torque_nm: torque });
  const points = [];
  grid.rpm.forEach((r, k) => {
    if (grid.feasible[k] && grid.eta_system[k] !== null) points.push({ x: r, y: grid.torque_nm[k], eta: grid.eta_system[k] });
  });
  const etas = points.map((p) => p.eta);
  const lo = Math.max(0, Math.min(...etas)), hi = Math.max(...etas);
  const colors = points.map((p) => etaColor(p.eta, lo, hi));
  if (charts["chart-map"]) charts["chart-map"].destroy();
  charts["chart-map"] = new Chart($("chart-map"), {
    type: "scatter",
    data: {
      datasets: [
        { label: "propeller", data: rows.map((r) => ({ x: r.rpm, y: r.torque_nm })), showLine: true, borderColor: "#000",
          backgroundColor: "#000", pointRadius: 3, order: 0 },
        { label: `η system (blue ${(100 * lo).toFixed(0)} % .. red ${(100 * hi).toFixed(0)} %)`, data: points, pointStyle: "rect", pointRadius: 4,
          backgroundColor: colors, borderWidth: 0, order: 1 },
      ],
    },
    options: {
      animation: false, responsive: true, maintainAspectRatio: false,
      plugins: {
        title: { display: true, text: `system efficiency over torque and speed at ${doc.vdc_v} V` },
        tooltip: { callbacks: { label: (c) => (c.raw.eta !== undefined ? `η ${(100 * c.raw.eta).toFixed(1)} %` : `${c.raw.x.toFixed(0)} rpm`) } },
      },
      scales: { x: { title: { display: true, text: "rpm" } }, y: { title: { display: true, text: "torque N·m" } } },
    },
  });
}

async function runDrive(ev) {
  if (ev) ev.preventDefault();
  showError("drive-error", null);
  const t0 = performance.now();
  try {
    const doc = await api("/api/simulate", driveRequest());
    const ms = performance.now() - t0;
    if (doc.prop) renderPropTable(doc); else renderMotorTable(doc);
    $("drive-title").textContent = `${doc.motor} + ${doc.esc}${doc.prop ? " + " + doc.prop : ""} at ${doc.vdc_v} V` +
      ` (${ms.toFixed(0)} ms)`;
    $("drive-notes").textContent = doc.assumed ? `results rest on assumed catalog values (${doc.assumed})` : "";
    document.body.dataset.driveMs = ms.toFixed(1);
    if (doc.prop) {
      await renderEfficiencyMap(doc);
    } else if (charts["chart-map"]) {
      charts["chart-map"].destroy();
      delete charts["chart-map"];
    }
  } catch (err) {
    showError("drive-error", err);
  }
}

async function initDrive() {
  try {
    const [motors, escs, props] = await Promise.all(["motors", "escs", "props"].map(catalogKind));
    catalogCache["motors:resolved"] = motors;
    catalogCache["escs:resolved"] = escs;
    catalogCache["props:resolved"] = props;
    picker("motor-filter", "motor", motors, "emax_1900kv_paper", false);
    picker("esc-filter", "esc", escs, "multistar_30a_paper", false);
    picker("prop-filter", "prop", props, "fu_p_apc_8x3.8sf", true);
    await runDrive();
    document.body.dataset.ready = "1";
  } catch (err) {
    showError("drive-error", err);
  }
}

// --- catalog browser
const VALUE_SKIP = new Set(["source", "derived", "static_table", "j_tables", "id", "name"]);
async function listCatalog(ev) {
  if (ev) ev.preventDefault();
  showError("cat-error", null);
  const kind = $("cat-kind").value;
  const q = new URLSearchParams({ kind });
  if (kind === "motors") {
    if ($("cat-kv-min").value) q.set("kv_min", $("cat-kv-min").value);
    if ($("cat-kv-max").value) q.set("kv_max", $("cat-kv-max").value);
  }
  if ($("cat-mass-max").value) q.set("mass_max_kg", $("cat-mass-max").value);
  try {
    const doc = await api(`/api/catalog?${q}`);
    const words = $("cat-text").value.toLowerCase().split(/\s+/).filter(Boolean);
    const list = doc[kind].filter((e) => words.every((w) => `${e.id} ${e.name}`.toLowerCase().includes(w)));
    $("cat-count").textContent = `${list.length} of ${doc[kind].length} ${kind}` + (list.length > 500 ? " (first 500 shown)" : "");
    const tbody = header($("cat-table"), [["id", "text"], ["name", "text"], ["Kv rpm/V"], ["mass g"], ["I max A"], ["tier", "text"]]);
    for (const e of list.slice(0, 500)) {
      const tr = tbody.insertRow();
      tr.className = "clickable";
      cell(tr, e.id, "text");
      cell(tr, e.name, "text");
      cell(tr, fmt(e.kv_rpm_per_v, 0));
      cell(tr, fmt(1000 * e.mass_kg, 0));
      cell(tr, fmt(e.max_current_a, 1));
      cell(tr, (e.source && e.source.tier) || "-", "text");
      tr.addEventListener("click", () => showEntry(e.id));
    }
  } catch (err) {
    showError("cat-error", err);
  }
}

async function showEntry(id) {
  showError("cat-error", null);
  try {
    const e = await api(`/api/catalog/${encodeURIComponent(id)}`);
    const box = $("cat-entry");
    box.replaceChildren();
    const h = document.createElement("h2");
    h.textContent = `${e.name} (${e.id})`;
    box.appendChild(h);
    const src = e.source || {};
    const p = document.createElement("p");
    p.innerHTML = "";
    p.append(`tier `, Object.assign(document.createElement("span"), { className: "tier", textContent: src.tier || "-" }),
      `; ${src.dataset || ""}${src.reference ? ", " + src.reference : ""}`);
    box.appendChild(p);
    if (src.note) box.appendChild(Object.assign(document.createElement("p"), { className: "notes", textContent: src.note }));
    const table = document.createElement("table");
    table.id = "cat-entry-values";
    const tbody = header(table, [["key", "text"], ["value"], ["provenance", "text"]]);
    const prov = src.values || {};
    for (const [k, v] of Object.entries(e)) {
      if (VALUE_SKIP.has(k) || typeof v === "object") continue;
      const tr = tbody.insertRow();
      cell(tr, k, "text");
      cell(tr, typeof v === "number" ? String(+v.toPrecision(6)) : String(v));
      cell(tr, prov[k] || "-", "text");
    }
    box.appendChild(table);
    const raw = document.createElement("details");
    raw.append(Object.assign(document.createElement("summary"), { textContent: "the entry as JSON (catalog show)" }),
      Object.assign(document.createElement("pre"), { textContent: JSON.stringify(e, null, 2) }));
    box.appendChild(raw);
  } catch (err) {
    showError("cat-error", err);
  }
}

// --- mission optimizer
async function loadExamples() {
  try {
    const doc = await api("/api/examples");
    const sel = $("mission-example");
    sel.replaceChildren(...doc.examples.map((n) => new Option(n, n, false, n === "quadcopter_1p5kg")));
  } catch (err) {
    showError("mission-error", err);
  }
}

// The mission as a form: the scalar and list values of vehicle, air, battery, constraints and
// objective, and a table of the segments. Editing a field writes the JSON text; editing the
// text redraws the form. Lists are written "3, 4"; an empty field removes the key.
const FORM_SECTIONS = ["vehicle", "air", "battery", "constraints", "objective"];
function fieldText(v) { return Array.isArray(v) ? v.join(", ") : String(v); }
function fieldValue(text, old) {
  const one = (t) => (t !== "" && !isNaN(Number(t)) && typeof (Array.isArray(old) ? old[0] : old) !== "string" ? Number(t) : t);
  if (Array.isArray(old) || text.includes(",")) return text.split(",").map((t) => one(t.trim())).filter((t) => t !== "");
  return one(text.trim());
}
function formInput(obj, key, onChange) {
  const input = document.createElement("input");
  input.value = fieldText(obj[key]);
  if (typeof obj[key] === "string" || Array.isArray(obj[key])) input.className = "text";
  input.addEventListener("change", () => {
    if (input.value.trim() === "") delete obj[key]; else obj[key] = fieldValue(input.value, obj[key]);
    onChange();
  });
  return input;
}
function renderMissionForm() {
  const box = $("mission-form-fields");
  box.replaceChildren();
  let m;
  try { m = JSON.parse($("mission-json").value); } catch (e) { return; }
  if (!m || typeof m !== "object") return;
  const write = () => { $("mission-json").value = JSON.stringify(m, null, 2); };
  for (const section of FORM_SECTIONS) {
    if (!m[section] || typeof m[section] !== "object" || Array.isArray(m[section])) continue;
    const fs = document.createElement("fieldset");
    fs.appendChild(Object.assign(document.createElement("legend"), { textContent: section }));
    for (const [k, v] of Object.entries(m[section])) {
      if (v !== null && typeof v === "object" && !Array.isArray(v)) continue;
      const label = document.createElement("label");
      label.append(k, formInput(m[section], k, write));
      fs.appendChild(label);
    }
    box.appendChild(fs);
  }
  if (Array.isArray(m.segments)) {
    const keys = [...new Set(m.segments.flatMap((s) => Object.keys(s)))];
    const table = document.createElement("table");
    table.id = "mission-segments-form";
    const tbody = header(table, keys.map((k) => [k, "text"]));
    for (const seg of m.segments) {
      const tr = tbody.insertRow();
      for (const k of keys) {
        const td = tr.insertCell();
        if (k in seg && (typeof seg[k] !== "object" || Array.isArray(seg[k]))) td.appendChild(formInput(seg, k, write));
      }
    }
    const fs = document.createElement("fieldset");
    fs.appendChild(Object.assign(document.createElement("legend"), { textContent: "segments" }));
    const wrap = Object.assign(document.createElement("div"), { className: "scroll" });
    wrap.appendChild(table);
    fs.appendChild(wrap);
    box.appendChild(fs);
  }
}

async function loadMissionFile() {
  showError("mission-error", null);
  const file = $("mission-file").files[0];
  if (!file) return;
  $("mission-json").value = await file.text();
  $("mission-status").textContent = `loaded ${file.name}`;
  renderMissionForm();
}

async function loadExample() {
  showError("mission-error", null);
  try {
    const res = await fetch(`/examples/${encodeURIComponent($("mission-example").value)}.json`);
    if (!res.ok) throw new Error(`example ${$("mission-example").value}: HTTP ${res.status}`);
    $("mission-json").value = await res.text();
    $("mission-status").textContent = `loaded ${$("mission-example").value}`;
    renderMissionForm();
    $("mission-table").replaceChildren();
    $("mission-detail").replaceChildren();
  } catch (err) {
    showError("mission-error", err);
  }
}

function objectiveText(r, v) {
  if (r.objective_unit === "s") return `${fmt(v / 60, 2)} min`;
  return `${fmt(v, 3)} ${r.objective_unit || ""}`;
}

function renderResults(doc, ms) {
  const res = doc.results;
  document.body.dataset.optimizeMs = ms.toFixed(0);
  $("mission-status").textContent = `${res.length} designs; ${doc.combinations} combinations, ${doc.searched} evaluated ` +
    `exactly, ${doc.pruned} pruned by safe bounds; search ${fmt(doc.seconds, 2)} s, answer in ${fmt(ms / 1000, 2)} s` +
    (doc.interrupted ? " (stopped: the best found so far)" : "");
  const tbody = header($("mission-table"), [["#"], ["motor", "text"], ["ESC", "text"], ["propeller", "text"],
    ["battery", "text"], ["cells"], ["objective"], ["credible range"], ["feasible", "text"], ["mass kg"], ["T/W"],
    ["hover throttle %"]]);
  res.forEach((r, i) => {
    const tr = tbody.insertRow();
    tr.className = "clickable" + (i === 0 ? " pick" : "");
    cell(tr, String(i + 1));
    for (const [kind, id] of [["motors", r.motor], ["escs", r.esc], ["props", r.prop]]) {
      const name = nameOf(kind, id);
      cell(tr, name ? `${id} (${name})` : id, "text");
    }
    cell(tr, r.battery, "text");
    cell(tr, String(r.cells));
    cell(tr, objectiveText(r, r.objective));
    cell(tr, r.objective_range ? `${objectiveText(r, r.objective_range[0])} - ${objectiveText(r, r.objective_range[1])}` : "-");
    cell(tr, r.feasible ? "yes" : "no", "text");
    cell(tr, fmt(r.total_mass_kg, 3));
    cell(tr, fmt(r.thrust_to_weight, 2));
    cell(tr, r.summary ? fmt(100 * r.summary.hover_throttle, 1) : "-");
    tr.addEventListener("click", () => renderSegments(r, i));
  });
  if (!res.length && doc.no_design_because) $("mission-status").textContent += `: ${JSON.stringify(doc.no_design_because)}`;
  if (res.length) renderSegments(res[0], 0);
}

// The Pareto front as optimize --plot draws it: every evaluated combination, the front, the picks.
function renderPareto(pareto, results) {
  if (typeof Chart === "undefined" || !pareto) return;
  if (charts["chart-pareto"]) charts["chart-pareto"].destroy();
  const xy = (pairs) => pairs.filter((p) => p[1] !== null).map(([x, y]) => ({ x, y }));
  const display = (r) => (r.objective_unit === "s" ? r.objective / 60 : r.objective);
  const unit = pareto.unit.trim();
  charts["chart-pareto"] = new Chart($("chart-pareto"), {
    type: "scatter",
    data: {
      datasets: [
        { label: `evaluated (${pareto.evaluated})`, data: xy(pareto.all), pointRadius: 1.5, backgroundColor: "#9a9a9a" },
        { label: "Pareto front", data: xy(pareto.front), showLine: true, borderColor: "#d62728", backgroundColor: "#d62728", pointRadius: 3 },
        { label: "top picks", data: results.map((r) => ({ x: r.propulsion_mass_kg, y: display(r) })), pointRadius: 7,
          pointStyle: "circle", borderColor: "#1f77b4", backgroundColor: "rgba(31,119,180,0.2)", borderWidth: 2 },
      ],
    },
    options: {
      animation: false, responsive: true, maintainAspectRatio: false,
      plugins: { title: { display: true, text: `objective (${unit}) vs propulsion mass` } },
      scales: { x: { title: { display: true, text: "propulsion mass kg" } }, y: { title: { display: true, text: unit } } },
    },
  });
}

function renderSegments(r, i) {
  const box = $("mission-detail");
  box.replaceChildren(Object.assign(document.createElement("h2"), { textContent: `#${i + 1}: operating point per segment` }));
  if (!r.segments) return;
  const table = document.createElement("table");
  const tbody = header(table, [["segment", "text"], ["type", "text"], ["s"], ["rpm"], ["throttle %"], ["torque N·m"],
    ["IDC A"], ["VDC V"], ["PDC W"], ["η system"], ["SOC end %"]]);
  for (const s of r.segments) {
    const tr = tbody.insertRow();
    cell(tr, s.name, "text");
    cell(tr, s.type, "text");
    [fmt(s.duration_s, 0), fmt(s.rpm, 0), fmt(100 * s.throttle, 1), fmt(s.torque_nm, 4), fmt(s.idc_a, 2), fmt(s.vdc_v, 2),
      fmt(s.pdc_w, 1), fmt(s.eta_system, 3), fmt(100 * s.soc_end, 1)].forEach((t) => cell(tr, t));
  }
  const wrap = Object.assign(document.createElement("div"), { className: "scroll" });
  wrap.appendChild(table);
  box.appendChild(wrap);
  if (r.warnings && r.warnings.length) {
    box.appendChild(Object.assign(document.createElement("p"), { className: "notes", textContent: r.warnings.join("\n") }));
  }
}

// Optimize as a job (POST /api/jobs/optimize): its progress polled, Cancel stops it with the
// best so far (as Ctrl-C on the command line).
let missionJob = null;
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function runMission(ev) {
  ev.preventDefault();
  showError("mission-error", null);
  let mission;
  try {
    if (!$("mission-json").value.trim()) await loadExample();
    mission = JSON.parse($("mission-json").value);
  } catch (err) {
    showError("mission-error", new Error(`mission JSON: ${err.message}`));
    return;
  }
  const button = $("mission-run"), cancel = $("mission-cancel"), bar = $("mission-progress");
  button.disabled = true;
  const t0 = performance.now();
  try {
    const body = { mission, top: Number($("mission-top").value) };
    if ($("mission-time").value) body.time_limit_s = Number($("mission-time").value);
    missionJob = (await api("/api/jobs/optimize", body)).job;
    cancel.disabled = false;
    bar.hidden = false;
    bar.value = 0;
    for (let wait = 20; ; wait = Math.min(2 * wait, 100)) {
      const st = await api(`/api/jobs/${missionJob}`);
      const p = st.progress;
      bar.value = p.fraction;
      $("mission-status").textContent = `${st.state === "queued" ? "waiting for a free slot" : "optimizing"}... ` +
        `${st.seconds.toFixed(1)} s, ${(100 * p.fraction).toFixed(0)} % done, ${p.searched} evaluated` +
        (p.best_objective !== null ? `, best ${p.best_objective.toFixed(2)}${p.unit}` : "");
      if (st.state === "done") {
        renderResults(st.result, performance.now() - t0);
        renderPareto(st.pareto, st.result.results);
        break;
      }
      if (st.state === "failed") throw new Error(st.error.error);
      await sleep(wait);
    }
  } catch (err) {
    $("mission-status").textContent = "";
    showError("mission-error", err);
  } finally {
    missionJob = null;
    button.disabled = false;
    cancel.disabled = true;
    bar.hidden = true;
  }
}

async function cancelMission() {
  if (!missionJob) return;
  try {
    await api(`/api/jobs/${missionJob}/cancel`, {});
  } catch (err) {
    showError("mission-error", err);
  }
}

// --- calibration and diagnosis of uploaded logs
// A file as the API takes it: UTF-8 text as text, anything else (a spreadsheet's Latin-1 re-save)
// as base64 of its bytes.
async function logOf(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  try {
    return { name: file.name, text: new TextDecoder("utf-8", { fatal: true }).decode(bytes) };
  } catch (e) {
    let bin = "";
    for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
    return { name: file.name, base64: btoa(bin) };
  }
}

function keyValueTable(rows) {
  const table = document.createElement("table");
  const tbody = header(table, [["check", "text"], ["passed", "text"], ["value"], ["limit"], ["detail", "text"]]);
  for (const c of rows) {
    const tr = tbody.insertRow();
    cell(tr, c.name, "text");
    cell(tr, c.passed ? "yes" : "NO", "text");
    cell(tr, typeof c.value === "number" ? String(+c.value.toPrecision(4)) : "-");
    cell(tr, typeof c.limit === "number" ? String(+c.limit.toPrecision(4)) : "-");
    cell(tr, c.detail || "", "text");
  }
  return table;
}

function download(name, doc) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([JSON.stringify(doc, null, 2) + "\n"], { type: "application/json" }));
  a.download = name;
  a.textContent = `download ${name}`;
  return a;
}

function renderCalibration(doc) {
  const box = $("cal-result");
  box.replaceChildren();
  $("cal-status").textContent = `calibrate: ${doc.summary}`;
  if (doc.advice) box.appendChild(Object.assign(document.createElement("p"), { className: "notes", textContent: doc.advice }));
  box.appendChild(keyValueTable(doc.checks || []));
  const params = document.createElement("table");
  params.id = "cal-params";
  const tbody = header(params, [["parameter", "text"], ["value"], ["std error"], ["identifiable", "text"]]);
  for (const [k, se] of Object.entries(doc.stderr || {})) {
    const v = k in (doc.motor || {}) ? doc.motor[k] : (doc.esc || {})[k];
    const tr = tbody.insertRow();
    cell(tr, k, "text");
    cell(tr, typeof v === "number" ? String(+v.toPrecision(6)) : "-");
    cell(tr, typeof se === "number" ? String(+se.toPrecision(3)) : "-");
    cell(tr, doc.identifiable && k in doc.identifiable ? (doc.identifiable[k] ? "yes" : "no") : "-", "text");
  }
  box.appendChild(Object.assign(document.createElement("h2"), { textContent: "fitted parameters" }));
  box.appendChild(params);
  const ho = doc.held_out;
  if (ho && ho.idc) {
    box.appendChild(Object.assign(document.createElement("p"), {
      textContent: `held out (${ho.folds} folds), dynosize / plain DC model: DC current ${fmt(ho.idc.median_abs_percent, 2)} % / ` +
        `${ho.dc_baseline ? fmt(ho.dc_baseline.idc.median_abs_percent, 2) : "-"} %, speed at the torque ` +
        `${fmt(ho.omega_at_torque.median_abs_percent, 2)} % / ${ho.dc_baseline ? fmt(ho.dc_baseline.omega_at_torque.median_abs_percent, 2) : "-"} %`,
    }));
  }
  if (doc.motor && doc.esc) {
    const p = document.createElement("p");
    p.appendChild(download(`${doc.motor.id}.json`, { motors: [doc.motor], escs: [doc.esc] }));
    p.append(" (a catalog file: use it with --catalog-add, or add it to your parts folder)");
    box.appendChild(p);
  }
  if (doc.warnings && doc.warnings.length) {
    box.appendChild(Object.assign(document.createElement("p"), { className: "notes", textContent: doc.warnings.join("\n") }));
  }
}

function renderDiagnosis(doc) {
  const box = $("cal-result");
  box.replaceChildren();
  $("cal-status").textContent = `diagnose: ${doc.summary}`;
  if (doc.advice) box.appendChild(Object.assign(document.createElement("p"), { className: "notes", textContent: doc.advice }));
  // What the log shows: the named causes, then what the extended model still misses.
  const lines = (doc.findings || []).map((f) => `${f.cause}: held-out error ${fmt(f.gain_percent, 1)} % lower`);
  for (const t of doc.remaining_trends || []) {
    lines.push(`${t.column}, still: ${t.text}` + (t.measurement ? ` (to separate them: ${t.measurement})` : ""));
  }
  if (lines.length) {
    const ul = document.createElement("ul");
    ul.id = "diag-findings";
    for (const l of lines) ul.appendChild(Object.assign(document.createElement("li"), { textContent: l }));
    box.appendChild(ul);
  }
  box.appendChild(keyValueTable(doc.checks || []));
  const raw = document.createElement("details");
  raw.append(Object.assign(document.createElement("summary"), { textContent: "findings and the extended model (diagnose --json)" }),
    Object.assign(document.createElement("pre"), { textContent: JSON.stringify({ findings: doc.findings, extended_model: doc.extended_model }, null, 2) }));
  box.appendChild(raw);
}

async function runLogs(kind) {
  showError("cal-error", null);
  const files = [...$("cal-files").files];
  if (!files.length) {
    showError("cal-error", new Error("choose one or more log files first"));
    return;
  }
  $("cal-status").textContent = `${kind}...`;
  try {
    const logs = await Promise.all(files.map(logOf));
    const common = { format: $("cal-format").value };
    if ($("cal-kv").value) common.kv_label = Number($("cal-kv").value);
    if (kind === "calibrate") {
      renderCalibration(await api("/api/calibrate", { logs, motor_id: $("cal-motor-id").value, esc_id: $("cal-esc-id").value, ...common }));
    } else {
      renderDiagnosis(await api("/api/diagnose", { log: logs[0], ...common }));
    }
  } catch (err) {
    $("cal-status").textContent = "";
    showError("cal-error", err);
  }
}

document.addEventListener("DOMContentLoaded", () => {
  for (const b of document.querySelectorAll(".tab")) b.addEventListener("click", () => showView(b.dataset.view));
  $("drive-form").addEventListener("submit", runDrive);
  for (const id of ["motor", "esc", "prop", "vdc", "rho"]) $(id).addEventListener("change", () => runDrive());
  $("cells").addEventListener("change", () => {
    const n = Number($("cells").value);
    if (n > 0) $("vdc").value = (3.7 * n).toFixed(2);
    runDrive();
  });
  $("catalog-form").addEventListener("submit", listCatalog);
  $("cat-kind").addEventListener("change", () => listCatalog());
  $("mission-form").addEventListener("submit", runMission);
  $("mission-load").addEventListener("click", loadExample);
  $("mission-cancel").addEventListener("click", cancelMission);
  $("mission-file").addEventListener("change", loadMissionFile);
  $("mission-json").addEventListener("change", renderMissionForm);
  $("cal-form").addEventListener("submit", (ev) => { ev.preventDefault(); runLogs("calibrate"); });
  $("diag-run").addEventListener("click", () => runLogs("diagnose"));
  initDrive();
});
