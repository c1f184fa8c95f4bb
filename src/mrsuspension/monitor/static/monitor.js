// mrsuspension HiL monitor page (vanilla JS, no third-party code).
"use strict";
(function () {
  const token = new URLSearchParams(location.search).get("token");
  const q = token ? "?token=" + encodeURIComponent(token) : "";
  const KEEP = 10.0; // seconds shown
  const PLOTS = [
    { title: "drive current [A]: commanded i_cmd, measured i_dm, demand i_d", ch: ["i_cmd", "i_dm", "i_d"] },
    { title: "damper force [N]: measured F_dm, model F_dmod", ch: ["F_dm", "F_dmod"] },
    { title: "tire force F_T [N]", ch: ["F_T"] },
    { title: "z_s [m]", ch: ["z_s"] },
    { title: "z_s'' [m/s^2]", ch: ["z_s_ddot"] },
    { title: "z_u [m]", ch: ["z_u"] },
    { title: "z_u'' [m/s^2]", ch: ["z_u_ddot"] },
    { title: "stroke [m]: model x_d, measured x_m", ch: ["x_d", "x_m"] },
    { title: "z_r [m]", ch: ["z_r"] },
    { title: "z_r'' [m/s^2]", ch: ["z_r_ddot"] },
    { title: "body (half or full car): heave [m], pitch [rad], roll [rad]", ch: ["heave", "pitch", "roll"] },
  ];
  const COLORS = ["#c33", "#36c", "#999"];
  const MEASURES = ["T_as", "T_ds", "T_au", "T_du", "T_dr", "DLC"];
  const PRESETS = ["smooth", "medium-rough", "rough", "file"];
  const TRIGGERS = ["z_r", "z_s", "z_u", "x_d", "x_m", "F_dm", "F_T", "i_d", "i_cmd", "i_dm", "z_s_ddot"];
  const data = {}; // channel -> array
  let run = -1;
  let startedHere = -1;
  const monitor = { points: 0, measures: {}, status: {}, frames: 0, last: {}, range: {}, posts: [] };
  monitor.data = data;
  window.monitorState = monitor;

  const $ = (id) => document.getElementById(id);
  const plotsEl = $("plots");
  const canvases = PLOTS.map((p) => {
    const c = document.createElement("canvas");
    c.width = 600; c.height = 260; c.title = p.title;
    plotsEl.appendChild(c);
    return c;
  });
  for (const ch of TRIGGERS) {
    const o = document.createElement("option"); o.value = ch; o.textContent = ch;
    $("trigger").appendChild(o);
  }

  function rows(tableId, names) {
    const body = document.querySelector("#" + tableId + " tbody");
    const cells = {};
    for (const n of names) {
      const tr = document.createElement("tr");
      const id = tableId + "-" + n.replace(/[^A-Za-z0-9_]/g, "_");
      tr.innerHTML = "<td>" + n + "</td><td class='v' id='" + id + "'>-</td>";
      body.appendChild(tr);
      cells[n] = tr.lastChild;
    }
    return cells;
  }
  const measureCells = rows("measures", MEASURES);
  const healthCells = rows("health", ["state", "safety", "reason", "time [s]", "ticks", "misses",
    "in deadline", "dropped", "lost rows", "tick [us]", "tick max [us]", "late max [us]", "current [A]", "changes applied"]);

  // -- controller fields, built from the controller registry (GET api/controllers) ------
  // one field per option name (laws sharing an option share its field); blank: the
  // selected law's default (its placeholder)
  const laws = {}; // law -> its options (name, label, unit, default, min, max, choices)
  const lawInfo = {}; // law -> { vehicle: a whole-vehicle law, defaults: model -> option -> value }
  const lawFields = {}; // option name -> { label, text, field }
  const models = {}; // vehicle model -> { corners, sets } (GET api/vehicles)
  const sensingFields = []; // { label, field, kind, velocity: the estimators it belongs to }
  function rangeText(o) {
    const lo = o.min === null ? "-inf" : o.min;
    const hi = o.max === null ? "inf" : o.max;
    return "in " + (o.min_open ? "(" : "[") + lo + ", " + hi + (o.max_open ? ")" : "]") + (o.unit ? " " + o.unit : "");
  }
  function inRange(o) {
    return (v) => (o.min === null || (o.min_open ? v > o.min : v >= o.min)) &&
      (o.max === null || (o.max_open ? v < o.max : v <= o.max));
  }
  function buildControllers(forms) {
    const sel = $("controller");
    const box = $("controller_options");
    for (const c of forms.controllers) {
      laws[c.law] = c.options;
      lawInfo[c.law] = { vehicle: !!c.vehicle, defaults: c.defaults || {} };
      const item = document.createElement("option");
      item.value = c.law; item.textContent = c.law + (c.vehicle ? " (whole vehicle)" : "");
      item.dataset.vehicle = c.vehicle ? "1" : "0";
      sel.appendChild(item);
      for (const o of c.options) {
        let f = lawFields[o.name];
        if (!f) {
          const label = document.createElement("label");
          const text = document.createTextNode(o.label + " ");
          let field;
          if (o.choices) {  // a switch: applied at once while a run goes
            field = document.createElement("select");
            for (const ch of ["", ...o.choices]) {
              const x = document.createElement("option");
              x.value = ch; x.textContent = ch || "(law default)";
              field.appendChild(x);
            }
            field.addEventListener("change", applySwitch);
          } else {
            field = document.createElement("input");
          }
          field.name = o.name; field.id = o.name;
          label.appendChild(text); label.appendChild(field);
          box.appendChild(label);
          f = lawFields[o.name] = { label: label, text: text, field: field, laws: [] };
        }
        f.laws.push(c.law);
      }
    }
    sel.value = forms.default;
    monitor.controllers = forms;
    lawDefaults();
    showFields();
  }
  // the selected law's labels and defaults (fields typed into since the last start/apply kept);
  // a whole-vehicle law's defaults are those of the chosen model
  function lawDefaults() {
    const law = $("controller").value;
    const onModel = (lawInfo[law] && lawInfo[law].defaults[$("model").value]) || {};
    for (const o of laws[law] || []) {
      const f = lawFields[o.name];
      const dflt = o.name in onModel ? onModel[o.name] : o.default;
      f.text.textContent = o.label + " ";
      f.label.title = o.name + (o.choices ? ": " + o.choices.join(", ") : " " + rangeText(o));
      if (edited.has(o.name)) continue;
      if (o.choices) f.field.value = dflt === null ? "" : dflt;
      else { f.field.value = ""; f.field.placeholder = dflt === null ? "law default" : String(dflt); }
    }
  }

  // -- vehicle model, its set and rig corner, sensing (GET api/vehicles) -----------------
  function isCar() {
    const m = models[$("model").value];
    return !!(m && m.corners.length);
  }
  function fillSelect(sel, values, blank) {
    const keep = sel.value;
    sel.innerHTML = "";
    for (const v of (blank === undefined ? [] : [""]).concat(values)) {
      const x = document.createElement("option");
      x.value = v; x.textContent = v || blank;
      sel.appendChild(x);
    }
    if (values.includes(keep)) sel.value = keep;
  }
  function modelChoices() {  // the chosen model's sets and corners
    const m = models[$("model").value] || { corners: [], sets: [] };
    fillSelect($("set"), m.sets, "(model defaults)");
    fillSelect($("rig_corner"), m.corners);
  }
  function buildVehicles(forms) {
    for (const m of forms.models) {
      models[m.model] = m;
      const x = document.createElement("option");
      x.value = m.model; x.textContent = m.model;
      $("model").appendChild(x);
    }
    $("model").value = forms.default;
    for (const v of forms.sensing.velocity) {
      const x = document.createElement("option");
      x.value = v; x.textContent = v;
      $("velocity").appendChild(x);
    }
    $("velocity").value = forms.sensing.default;
    for (const f of forms.sensing.fields) {
      const label = document.createElement("label");
      const field = document.createElement("input");
      field.name = f.name; field.id = f.name;
      field.placeholder = f.name === "stroke_fs" ? "none: true stroke" : "default";
      label.title = f.name + (f.velocity ? " (" + f.velocity.join(", ") + ")" : "");
      label.appendChild(document.createTextNode(f.label + " "));
      label.appendChild(field);
      $("sensing_options").appendChild(label);
      sensingFields.push({ label: label, field: field, kind: f.kind, velocity: f.velocity, text: f.label });
    }
    monitor.vehicles = forms;
    modelChoices();
  }
  // hidden fields are disabled too: the form sends only what the chosen model, law and
  // estimator take
  function show(el, on) {
    el.style.display = on ? "" : "none";
    if (el.tagName === "FIELDSET") el.disabled = !on;
    else el.querySelectorAll("input, select").forEach((x) => { x.disabled = !on; });
  }
  function showFields() {
    const car = isCar();
    const sel = $("controller");
    for (const o of sel.options) o.hidden = !car && o.dataset.vehicle === "1";
    if (!car && lawInfo[sel.value] && lawInfo[sel.value].vehicle) {  // a car's law: back to the default
      sel.value = monitor.controllers.default;
      lawDefaults();
    }
    const law = sel.value;
    for (const f of Object.values(lawFields)) f.label.style.display = f.laws.includes(law) ? "" : "none";
    document.querySelectorAll("[data-car]").forEach((el) => show(el, (el.dataset.car === "1") === car));
    const vel = $("velocity").value;
    for (const f of sensingFields) show(f.label, !f.velocity || f.velocity.includes(vel));
    const exc = $("excitation").value;
    document.querySelectorAll("label[data-for]").forEach((l) => {
      l.style.display = l.dataset.for === exc ? "" : "none";
    });
  }
  function applySwitch() {  // switches apply at once while a run goes; the rest on Apply
    if (isCar()) return;  // a car is a new run (live changes are a quarter car's)
    if (["running", "startup"].includes(monitor.status.state)) send("api/apply", "change sent: applied between ticks");
  }
  $("controller").addEventListener("change", () => { lawDefaults(); showFields(); applySwitch(); });
  $("excitation").addEventListener("change", showFields);
  $("model").addEventListener("change", () => { modelChoices(); lawDefaults(); showFields(); });
  $("velocity").addEventListener("change", showFields);
  showFields();

  function setError(text) { $("error").textContent = text || ""; }
  function setNote(text) { $("note").textContent = text || ""; }

  function settings() {
    const out = {};
    new FormData($("settings")).forEach((v, k) => { out[k] = v; });
    return out;
  }

  // -- validation in the page (the server validates again) -------------------------------
  function num(s, key, label, test, rule) {
    const raw = String(s[key] === undefined ? "" : s[key]).trim();
    const v = Number(raw);
    if (raw === "" || !isFinite(v)) return key + " (" + label + ") must be a number; got '" + raw + "'";
    if (!test(v)) return key + " (" + label + ") must be " + rule + "; got " + raw;
    return null;
  }
  const pos = (v) => v > 0;
  function validate(s) {
    const checks = isCar() ? [] : [  // a car's parameters: its model and set
      ["sprung_mass", "m_s [kg]", pos, "> 0"],
      ["unsprung_mass", "m_u [kg]", pos, "> 0"],
      ["suspension_stiffness", "k_s [N/m]", pos, "> 0"],
      ["tire_stiffness", "k_t [N/m]", pos, "> 0"],
      ["tire_damping", "c_t [N s/m]", (v) => v >= 0, ">= 0"],
    ];
    checks.push(
      ["rate", "loop rate [Hz]", (v) => v >= 50 && v <= 5000, "in [50, 5000] Hz"],
      ["duration", "run [s]", (v) => v > 0 && v <= 3600, "in (0, 3600] s"],
      ["ramp_time", "ramp [s]", (v) => v > 0 && v <= 5, "in (0, 5] s"],
    );
    for (const f of sensingFields) {  // numbers; their ranges: the server's (the scenario's)
      if (!f.field.disabled && String(f.field.value).trim() !== "") {
        checks.push([f.field.name, f.text, () => true, "a number"]);
      }
    }
    for (const o of laws[s.controller] || []) {  // blank: the law's default
      if (!o.choices && String(s[o.name] === undefined ? "" : s[o.name]).trim() !== "") {
        checks.push([o.name, o.label, inRange(o), rangeText(o)]);
      }
    }
    const exc = s.excitation;
    if (exc === "harmonic") {
      checks.push(["frequency", "f [Hz]", pos, "> 0 Hz"]);
      checks.push(["amplitude", "a [m]", pos, "> 0 m"]);
    } else if (exc === "pulse") {
      checks.push(["height", "pulse height [m]", pos, "> 0 m"]);
      checks.push(["severity", "severity", pos, "> 0"]);
      checks.push(["speed", "speed [km/h]", pos, "> 0 km/h"]);
    } else if (exc === "road") {
      const p = String(s.profile || "").trim();
      if (!PRESETS.includes(p)) return "unknown road preset '" + p + "'; valid: " + PRESETS.join(", ");
      if (p === "file" && !String(s.road_file || "").trim()) return "road file: give a file name";
      checks.push(["road_speed", "speed [km/h]", pos, "> 0 km/h"]);
      checks.push(["scale", "scale", pos, "> 0"]);
    }
    for (const [key, label, test, rule] of checks) {
      const msg = num(s, key, label, test, rule);
      if (msg) return msg;
    }
    return null;
  }

  async function post(path, body) {
    monitor.posts.push(path);
    const r = await fetch(path + q, {
      method: "POST", headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body || {}),
    });
    const j = await r.json().catch(() => ({ error: "bad response " + r.status }));
    if (!r.ok) throw new Error(j.error || ("HTTP " + r.status));
    return j;
  }

  async function send(path, what) {
    setError(""); setNote("");
    const s = settings();
    const problem = validate(s);
    if (problem) { setError("refused: " + problem); return; }
    try {
      const info = await post(path, s);
      if (path === "api/start") startedHere = info.run;
      edited.clear();  // the run has what the form shows
      setNote(what);
    } catch (e) { setError(e.message); }
  }
  $("start").addEventListener("click", () => send("api/start", "run started"));
  $("apply").addEventListener("click", () => send("api/apply", "change sent: applied between ticks"));
  $("stop").addEventListener("click", async () => {
    try { await post("api/stop"); } catch (e) { setError(e.message); }
  });
  $("record").addEventListener("click", async () => {
    const action = monitor.acquisition && monitor.acquisition.recording ? "stop" : "start";
    try { monitor.acquisition = await post("api/record", { action: action }); showAcq(); }
    catch (e) { setError(e.message); }
  });
  $("acq_set").addEventListener("click", async () => {
    setError("");
    const body = {
      acq_period: $("acq_period").value, trigger: $("trigger").value,
      trigger_level: $("trigger_level").value, trigger_edge: $("trigger_edge").value,
      pre_trigger: $("pre_trigger").value, display_rate: $("display_rate").value,
    };
    const p = Number(body.acq_period);
    if (!(Number.isInteger(p) && p >= 1 && p <= 100000)) { setError("refused: acquisition period must be a whole number of ticks in [1, 100000]; got '" + body.acq_period + "'"); return; }
    const pre = Number(body.pre_trigger);
    if (!(pre >= 0 && pre <= 60)) { setError("refused: pre-trigger must be in [0, 60] s; got '" + body.pre_trigger + "'"); return; }
    if (!isFinite(Number(body.trigger_level)) || String(body.trigger_level).trim() === "") { setError("refused: trigger level must be a number"); return; }
    try { monitor.acquisition = await post("api/acquisition", body); showAcq(); }
    catch (e) { setError(e.message); }
  });

  function showAcq() {
    const a = monitor.acquisition || {};
    $("record").textContent = a.recording ? "Record stop" : "Record start";
    $("record").className = a.recording ? "recording" : "";
    const w = (a.windows || []).map((x) => fmt(x[0], 2) + "-" + (x[1] === null ? "..." : fmt(x[1], 2))).join(", ");
    $("acq_state").textContent = (a.recording ? "recording; " : "") + "windows: " + (w || "whole run") +
      "; every " + a.period + " tick(s)" + (a.trigger ? "; trigger " + a.trigger + " " + a.edge + " " + a.level + " (pre " + a.pre_trigger + " s)" : "") +
      "; display " + a.display_rate + " Hz";
  }

  function fmt(x, digits) {
    if (x === null || x === undefined || !isFinite(x)) return "-";
    return Number(x).toFixed(digits === undefined ? 3 : digits);
  }

  // fields the user has typed into since the last start/apply: a run's fields arriving
  // in a frame (on connecting, or a run started elsewhere) never overwrite them
  const edited = new Set();
  $("settings").addEventListener("input", (e) => { if (e.target.name) edited.add(e.target.name); });
  function fillFields(fields) {
    for (const [k, v] of Object.entries(fields || {})) {
      const el = document.querySelector("[name='" + k + "']");
      if (el && el.tagName === "INPUT" && !edited.has(k)) el.value = v;
    }
  }

  function onFrame(f) {
    monitor.frames += 1;
    if (f.run !== run || f.history) {
      run = f.run;
      for (const c of f.channels) data[c] = [];
      if (run !== startedHere && f.status && f.status.fields) fillFields(f.status.fields);
    }
    f.channels.forEach((c, i) => { for (const r of f.rows) data[c].push(r[i] === null ? NaN : r[i]); });
    const t = data.time || [];
    if (t.length) {
      const cut = t[t.length - 1] - KEEP;
      let n = 0;
      while (n < t.length && t[n] < cut) n++;
      if (n) for (const c of f.channels) data[c].splice(0, n);
    }
    monitor.points = (data.time || []).length;
    for (const c of f.channels) {
      const v = data[c] || [];
      monitor.last[c] = v.length ? v[v.length - 1] : null;
      let lo = Infinity, hi = -Infinity;
      for (const x of v) if (isFinite(x)) { if (x < lo) lo = x; if (x > hi) hi = x; }
      monitor.range[c] = [lo, hi];
    }
    monitor.measures = f.measures || {};
    monitor.status = f.status || {};
    monitor.acquisition = f.acquisition || {};
    for (const m of MEASURES) measureCells[m].textContent = fmt(monitor.measures[m]);
    $("window").textContent = monitor.measures.window ? "(last " + monitor.measures.window + " s)" : "";
    const s = monitor.status;
    const stopped = s.reason === "STOP pressed";
    let label = s.state || "idle";
    if (s.safe && (stopped || s.state === "ended")) label = (stopped ? "stopped" : "ended") + " - safe (i = 0)";
    else if (s.state === "tripped") label = "tripped - safe (i = 0)";
    $("state").textContent = label;
    $("state").className = "state " + (stopped ? "stopped" : (s.state || "idle"));
    const safety = s.safe ? "SAFE: current 0" + (s.state === "ended" ? ", at mid-stroke" : ", returning to mid-stroke")
      : (s.tripped ? "TRIPPED: " + s.reason : (s.state === "running" ? "limits armed" : ""));
    $("safety").textContent = safety;
    $("rig").textContent = s.rig ? "rig: " + s.rig + (s.corner ? ", corner " + s.corner + " of the " + (s.model || "car") : "") : "";
    const h = healthCells;
    h.state.textContent = s.state || "-";
    h.safety.textContent = safety || "-";
    h.reason.textContent = s.reason || "";
    h["time [s]"].textContent = fmt(s.time, 2);
    h.ticks.textContent = s.ticks === undefined ? "-" : s.ticks;
    h.misses.textContent = s.misses === undefined ? "-" : s.misses;
    h["in deadline"].textContent = s.ticks ? fmt(100 * (1 - s.misses / s.ticks), 2) + " %" : "-";
    h.dropped.textContent = s.dropped === undefined ? "-" : s.dropped;
    h["lost rows"].textContent = s.lost === undefined ? "-" : s.lost;
    h["tick [us]"].textContent = s.compute_mean ? fmt(s.compute_mean * 1e6, 0) : "-";
    h["tick max [us]"].textContent = s.compute_max ? fmt(s.compute_max * 1e6, 0) : "-";
    h["late max [us]"].textContent = s.lateness_max ? fmt(s.lateness_max * 1e6, 0) : "-";
    h["current [A]"].textContent = fmt(s.current, 3);
    h["changes applied"].textContent = s.applied === undefined ? "-" : s.applied;
    const ev = $("events");
    ev.innerHTML = "";
    for (const e of (f.events || []).slice(-6)) { const li = document.createElement("li"); li.textContent = e; ev.appendChild(li); }
    const dl = $("download");
    if (f.recording) { dl.href = "api/recording" + q; dl.className = ""; }
    else { dl.href = "#"; dl.className = "disabled"; }
    showAcq();
    scheduleDraw();
  }

  // redraw at most every 100 ms, in an animation frame: the page (and STOP) stays responsive
  let drawPending = false;
  let lastDraw = 0;
  function scheduleDraw() {
    if (drawPending) return;
    drawPending = true;
    const wait = Math.max(0, 100 - (performance.now() - lastDraw));
    setTimeout(() => requestAnimationFrame(() => { drawPending = false; lastDraw = performance.now(); draw(); }), wait);
  }

  function draw() {
    const t = data.time || [];
    PLOTS.forEach((p, k) => {
      const c = canvases[k];
      const g = c.getContext("2d");
      g.clearRect(0, 0, c.width, c.height);
      g.fillStyle = "#333"; g.font = "20px sans-serif";
      g.fillText(p.title, 8, 22);
      if (t.length < 2) return;
      let lo = Infinity, hi = -Infinity;
      for (const ch of p.ch) for (const v of data[ch] || []) { if (!isFinite(v)) continue; if (v < lo) lo = v; if (v > hi) hi = v; }
      if (!isFinite(lo)) return;
      if (!(hi > lo)) { hi = lo + 1e-9; lo = lo - 1e-9; }
      const t1 = t[t.length - 1], t0 = t1 - KEEP;
      const X = (x) => ((x - t0) / KEEP) * (c.width - 10) + 5;
      const Y = (y) => c.height - 8 - ((y - lo) / (hi - lo)) * (c.height - 40);
      g.fillText(fmt(hi, 4), c.width - 110, 44);
      g.fillText(fmt(lo, 4), c.width - 110, c.height - 10);
      p.ch.forEach((ch, j) => {
        const v = data[ch] || [];
        g.strokeStyle = COLORS[j % COLORS.length]; g.lineWidth = 2;
        g.beginPath();
        let pen = false;
        const stride = Math.max(1, Math.floor(v.length / 400));  // about 400 points a trace
        for (let i = 0; i < v.length; i += stride) {
          if (!isFinite(v[i])) { pen = false; continue; }
          if (!pen) { g.moveTo(X(t[i]), Y(v[i])); pen = true; } else g.lineTo(X(t[i]), Y(v[i]));
        }
        g.stroke();
      });
    });
  }

  function connect() {
    const proto = location.protocol === "https:" ? "wss://" : "ws://";
    const base = location.pathname.replace(/[^/]*$/, "");
    const ws = new WebSocket(proto + location.host + base + "ws" + q);
    ws.onmessage = (ev) => onFrame(JSON.parse(ev.data));
    ws.onclose = () => setTimeout(connect, 1000);
    monitor.socket = ws;
  }
  async function getJSON(path) {
    const r = await fetch(path + q);
    if (!r.ok) throw new Error(path + ": HTTP " + r.status);
    return r.json();
  }
  async function loadControllers() {
    try {
      const [vehicles, forms] = await Promise.all([getJSON("api/vehicles"), getJSON("api/controllers")]);
      buildVehicles(vehicles);
      buildControllers(forms);
      $("start").disabled = false;
      $("apply").disabled = false;
    } catch (e) { setError("controller list not loaded: " + e.message); }
  }
  draw();
  loadControllers().then(connect);  // the fields exist before a frame fills them
})();
