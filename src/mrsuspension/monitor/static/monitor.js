// mrsuspension HiL monitor page (vanilla JS, no third-party code).
"use strict";
(function () {
  const token = new URLSearchParams(location.search).get("token");
  const q = token ? "?token=" + encodeURIComponent(token) : "";
  const KEEP = 10.0; // seconds shown
  const PLOTS = [
    { title: "current [A]: controller i_z (red), drive i_d (blue)", ch: ["i_z", "i_d"] },
    { title: "damper force F_d [N]", ch: ["F_d"] },
    { title: "tire force F_T [N]", ch: ["F_T"] },
    { title: "z_s [m]", ch: ["z_s"] },
    { title: "z_s'' [m/s^2]", ch: ["z_s_ddot"] },
    { title: "z_u [m]", ch: ["z_u"] },
    { title: "x_d [m]", ch: ["x_d"] },
    { title: "z_r [m]", ch: ["z_r"] },
  ];
  const COLORS = ["#c33", "#36c"];
  const MEASURES = ["T_as", "T_ds", "T_au", "T_du", "T_dr", "DLC"];
  const data = {}; // channel -> array
  let run = -1;
  const monitor = { points: 0, measures: {}, status: {}, frames: 0 };
  window.monitorState = monitor;

  const plotsEl = document.getElementById("plots");
  const canvases = PLOTS.map((p) => {
    const c = document.createElement("canvas");
    c.width = 600; c.height = 260; c.title = p.title;
    plotsEl.appendChild(c);
    return c;
  });

  function rows(tableId, names) {
    const body = document.querySelector("#" + tableId + " tbody");
    const cells = {};
    for (const n of names) {
      const tr = document.createElement("tr");
      tr.innerHTML = "<td>" + n + "</td><td class='v' id='" + tableId + "-" + n + "'>-</td>";
      body.appendChild(tr);
      cells[n] = tr.lastChild;
    }
    return cells;
  }
  const measureCells = rows("measures", MEASURES);
  const healthCells = rows("health", ["state", "reason", "ticks", "misses", "dropped", "tick [us]", "tick max [us]"]);

  function showFields() {
    for (const sel of ["controller", "excitation"]) {
      const value = document.getElementById(sel).value;
      document.querySelectorAll("fieldset label[data-for]").forEach((l) => {
        const owner = l.closest("fieldset").querySelector("select").id;
        if (owner === sel) l.style.display = l.dataset.for === value ? "" : "none";
      });
    }
  }
  document.getElementById("controller").addEventListener("change", showFields);
  document.getElementById("excitation").addEventListener("change", showFields);
  showFields();

  function setError(text) { document.getElementById("error").textContent = text || ""; }

  function settings() {
    const out = {};
    new FormData(document.getElementById("settings")).forEach((v, k) => { out[k] = v; });
    return out;
  }

  async function post(path, body) {
    const r = await fetch(path + q, {
      method: "POST", headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body || {}),
    });
    const j = await r.json().catch(() => ({ error: "bad response " + r.status }));
    if (!r.ok) throw new Error(j.error || ("HTTP " + r.status));
    return j;
  }

  document.getElementById("start").addEventListener("click", async () => {
    setError("");
    try {
      await post("api/start", settings());
    } catch (e) { setError(e.message); }
  });
  document.getElementById("stop").addEventListener("click", async () => {
    try { await post("api/stop"); } catch (e) { setError(e.message); }
  });

  function fmt(x, digits) {
    if (x === null || x === undefined || !isFinite(x)) return "-";
    return Number(x).toFixed(digits === undefined ? 3 : digits);
  }

  function onFrame(f) {
    monitor.frames += 1;
    if (f.run !== run) {
      run = f.run;
      for (const c of f.channels) data[c] = [];
    }
    f.channels.forEach((c, i) => { for (const r of f.rows) data[c].push(r[i]); });
    const t = data.time || [];
    if (t.length) {
      const cut = t[t.length - 1] - KEEP;
      let n = 0;
      while (n < t.length && t[n] < cut) n++;
      if (n) for (const c of f.channels) data[c].splice(0, n);
    }
    monitor.points = (data.time || []).length;
    monitor.measures = f.measures || {};
    monitor.status = f.status || {};
    for (const m of MEASURES) measureCells[m].textContent = fmt(monitor.measures[m]);
    document.getElementById("window").textContent =
      monitor.measures.window ? "(last " + monitor.measures.window + " s)" : "";
    const s = monitor.status;
    const stateEl = document.getElementById("state");
    const label = s.state === "stopped" || s.state === "completed" || s.state === "ended"
      ? s.state + " - safe (i = 0)" : (s.state || "idle");
    stateEl.textContent = label;
    stateEl.className = "state " + (s.state || "idle");
    healthCells.state.textContent = s.state || "-";
    healthCells.reason.textContent = s.reason || "";
    healthCells.ticks.textContent = s.ticks === undefined ? "-" : s.ticks;
    healthCells.misses.textContent = s.misses === undefined ? "-" : s.misses;
    healthCells.dropped.textContent = s.dropped === undefined ? "-" : s.dropped;
    healthCells["tick [us]"].textContent = s.compute_mean ? fmt(s.compute_mean * 1e6, 0) : "-";
    healthCells["tick max [us]"].textContent = s.compute_max ? fmt(s.compute_max * 1e6, 0) : "-";
    const dl = document.getElementById("download");
    if (f.recording) { dl.href = "api/recording" + q; dl.className = ""; }
    else { dl.href = "#"; dl.className = "disabled"; }
    draw();
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
      for (const ch of p.ch) for (const v of data[ch]) { if (v < lo) lo = v; if (v > hi) hi = v; }
      if (!(hi > lo)) { hi = lo + 1e-9; lo = lo - 1e-9; }
      const t1 = t[t.length - 1], t0 = t1 - KEEP;
      const X = (x) => ((x - t0) / KEEP) * (c.width - 10) + 5;
      const Y = (y) => c.height - 8 - ((y - lo) / (hi - lo)) * (c.height - 40);
      g.fillText(fmt(hi, 4), c.width - 110, 22);
      g.fillText(fmt(lo, 4), c.width - 110, c.height - 10);
      p.ch.forEach((ch, j) => {
        const v = data[ch];
        g.strokeStyle = COLORS[j % COLORS.length]; g.lineWidth = 2;
        g.beginPath();
        for (let i = 0; i < v.length; i++) {
          if (i === 0) g.moveTo(X(t[i]), Y(v[i])); else g.lineTo(X(t[i]), Y(v[i]));
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
  connect();
  draw();
})();
